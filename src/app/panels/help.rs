//! The help overlay (`?`, F1): every control from [`CONTROLS`], centred over the view. Where the
//! terminal is too narrow for a key column beside an action column, each control takes two rows
//! (the keys, then the action indented and wrapped); where it is too short for every row, ↑↓,
//! PageUp/PageDown and the wheel scroll it and the title says so. Any other key closes it.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::Line;
use ratatui::widgets::{Block, Clear, Paragraph, Widget};

use crate::app::input::keys::CONTROLS;

/// Columns between the border and the text, each side: the widest keys touched the left border.
const PAD: usize = 1;

/// The overlay's lines for a box `inner` columns wide (inside the border and padding): two columns
/// when they fit, else keys above their wrapped action.
fn lines(inner: usize) -> Vec<Line<'static>> {
    let keys_width = CONTROLS
        .iter()
        .map(|(k, _)| k.chars().count())
        .max()
        .unwrap_or(0);
    let action_width = CONTROLS
        .iter()
        .map(|(_, a)| a.chars().count())
        .max()
        .unwrap_or(0);
    let pad = " ".repeat(PAD);
    if keys_width + 2 + action_width <= inner {
        let mut out: Vec<Line<'static>> = CONTROLS
            .iter()
            .map(|(keys, action)| Line::from(format!("{pad}{keys:>keys_width$}  {action}")))
            .collect();
        out.extend(scene_lines(inner));
        return out;
    }
    let bold = Style::default().add_modifier(Modifier::BOLD);
    let mut out = Vec::new();
    for (keys, action) in CONTROLS {
        if !keys.is_empty() {
            out.push(Line::styled(format!("{pad}{keys}"), bold));
        }
        for part in wrap(action, inner.saturating_sub(2).max(8)) {
            out.push(Line::from(format!("{pad}  {part}")));
        }
    }
    out.extend(scene_lines(inner));
    out
}

/// The built-in scenes `n` and `N` cycle through, wrapped to `inner` columns. They were the
/// bottom border's title, which holds 69 characters at 80 columns: seven names fitted, twelve do
/// not.
fn scene_lines(inner: usize) -> Vec<Line<'static>> {
    let names: Vec<&str> = crate::scene::builtin_scenes()
        .iter()
        .map(|(name, _)| *name)
        .collect();
    let text = format!("scenes (n, N): {}", names.join(" "));
    let pad = " ".repeat(PAD);
    wrap(&text, inner.max(8))
        .into_iter()
        .map(|part| Line::from(format!("{pad}{part} ")))
        .collect()
}

/// `text` in lines of at most `width` columns, broken at spaces (a longer word is cut).
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let needed = line.chars().count() + usize::from(!line.is_empty()) + word.chars().count();
        if needed > width && !line.is_empty() {
            out.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    out.push(line);
    out
}

/// The widest the overlay gets: both columns, the padding and the border.
fn full_width() -> u16 {
    let keys = CONTROLS.iter().map(|(k, _)| k.chars().count()).max();
    let actions = CONTROLS.iter().map(|(_, a)| a.chars().count()).max();
    (keys.unwrap_or(0) + 2 + actions.unwrap_or(0) + 2 * PAD + 2) as u16
}

/// The help overlay over `view`, scrolled down `scroll` rows.
pub struct HelpOverlay {
    pub scroll: u16,
}

impl HelpOverlay {
    /// The box's cells and its lines for `view`.
    fn layout(view: Rect) -> (Rect, Vec<Line<'static>>) {
        let width = full_width().min(view.width);
        let inner = usize::from(width.saturating_sub(2)).saturating_sub(2 * PAD);
        let lines = lines(inner);
        let height = (lines.len() as u16 + 2).min(view.height);
        let [_, middle, _] = Layout::horizontal([
            Constraint::Fill(1),
            Constraint::Length(width),
            Constraint::Fill(1),
        ])
        .areas(view);
        let [_, popup, _] = Layout::vertical([
            Constraint::Fill(1),
            Constraint::Length(height),
            Constraint::Fill(1),
        ])
        .areas(middle);
        (popup, lines)
    }

    /// The most the overlay scrolls in `view`: 0 when every line shows.
    pub fn max_scroll(view: Rect) -> u16 {
        let (popup, lines) = Self::layout(view);
        (lines.len() as u16).saturating_sub(popup.height.saturating_sub(2))
    }
}

impl Widget for HelpOverlay {
    fn render(self, view: Rect, buf: &mut Buffer) {
        let (popup, lines) = Self::layout(view);
        let max_scroll = Self::max_scroll(view);
        let scroll = self.scroll.min(max_scroll);
        Clear.render(popup, buf);
        let title = if max_scroll > 0 {
            let shown = popup.height.saturating_sub(2);
            let last = (scroll + shown).min(lines.len() as u16);
            // Short enough for a 40-column box: which rows show, of how many.
            format!(
                " ↑↓ {}-{last}/{} · other keys close ",
                scroll + 1,
                lines.len()
            )
        } else {
            " nudge · any key closes ".to_string()
        };
        Paragraph::new(lines)
            .scroll((scroll, 0))
            .block(Block::bordered().title(title))
            .style(Style::default().fg(Color::White).bg(Color::Black))
            .render(popup, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(view: Rect, scroll: u16) -> String {
        let mut buf = Buffer::empty(view);
        HelpOverlay { scroll }.render(view, &mut buf);
        (0..view.height)
            .map(|y| {
                (0..view.width)
                    .map(|x| buf[(x, y)].symbol().to_string())
                    .collect::<String>()
                    + "\n"
            })
            .collect()
    }

    #[test]
    fn the_help_overlay_fits_an_80_column_terminal_uncut_and_lists_the_scenes() {
        // 21 controls, 2 rows of scenes and the borders.
        let view = Rect::new(0, 0, 80, 25);
        assert_eq!(HelpOverlay::max_scroll(view), 0);
        let text = text(view, 0);
        for (name, _) in crate::scene::builtin_scenes() {
            assert!(
                text.contains(&format!(" {name} ")),
                "{name} missing:\n{text}"
            );
        }
        assert!(text.contains("any key closes"), "{text}");
        for (keys, action) in CONTROLS {
            assert!(text.contains(keys), "{keys} missing:\n{text}");
            assert!(
                text.contains(&format!("{action} ")),
                "{action} cut:\n{text}"
            );
        }
        // No row touches the left border (the widest keys did).
        for line in text.lines() {
            assert!(!line.contains("│m"), "{line}");
        }
    }

    #[test]
    fn a_wrapped_line_breaks_at_spaces() {
        assert_eq!(
            wrap("push / pull the body", 10),
            ["push /", "pull the", "body"]
        );
        assert_eq!(wrap("short", 10), ["short"]);
    }
}
