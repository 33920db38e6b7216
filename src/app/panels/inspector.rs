//! The inspector panel (`i`): the selected body's and the whole world's figures, read from the
//! world's read-only views each frame, as a ratatui widget on the right of the screen.
//!
//! The panel is a column of sections (the body, the world, then whatever the app adds: the step
//! profile) and the charts below them; a section is drawn only if it fits whole, and the charts take
//! the rows left, so a small terminal keeps the first sections and drops the rest rather than
//! cutting lines.

use glam::Vec3;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Paragraph, Widget};

use crate::app::panels::charts::{Charts, History};
use crate::app::panels::joint_view::JointReport;
use crate::geometry::Shape;
use crate::physics::{BodyId, World};

/// Panel width in columns on a wide terminal, and on a narrow one (the 80-column case).
pub const WIDE_PANEL_COLS: u16 = 36;
pub const NARROW_PANEL_COLS: u16 = 29;
/// Terminals at least this wide get the wide panel.
pub const WIDE_TERMINAL_COLS: u16 = 110;
/// The scene keeps at least this many columns beside the panel; narrower terminals get no panel.
pub const MIN_SCENE_COLS: u16 = 32;

/// The panel's width for a terminal `cols` wide (0: no room for it).
pub fn panel_cols(cols: u16) -> u16 {
    let width = if cols >= WIDE_TERMINAL_COLS {
        WIDE_PANEL_COLS
    } else {
        NARROW_PANEL_COLS
    };
    if cols >= width + MIN_SCENE_COLS {
        width
    } else {
        0
    }
}

/// What a body is doing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BodyState {
    Awake,
    Asleep,
    /// Static at run time (middle click).
    Frozen,
    /// Static in the scene file.
    Scenery,
}

impl BodyState {
    pub fn name(self) -> &'static str {
        match self {
            BodyState::Awake => "awake",
            BodyState::Asleep => "asleep",
            BodyState::Frozen => "frozen",
            BodyState::Scenery => "scenery",
        }
    }
}

/// The selected body's figures, as the world has them.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyReport {
    pub id: BodyId,
    pub shape: Shape,
    /// kg.
    pub mass: f32,
    /// Principal moments of inertia (the inertia tensor's diagonal in the body frame), kg·m².
    pub inertia: Vec3,
    /// Centre of mass, world, m.
    pub position: Vec3,
    /// m/s, world.
    pub velocity: Vec3,
    /// rad/s, world.
    pub angular_velocity: Vec3,
    /// J.
    pub kinetic_energy: f32,
    /// Touching contact manifolds the body is part of.
    pub contacts: usize,
    /// Deepest penetration among them, m (≥ 0), as the manifolds measured it (at the start of the
    /// last step: the world's own `max_penetration` is taken after it, and is 0 for sleeping piles).
    pub penetration: f32,
    pub state: BodyState,
    /// Its name in the scene file, if it has one (the world has none: the app gives it).
    pub name: Option<String>,
}

impl BodyReport {
    /// The report of body `id`; `scenery` says whether the scene declared it static.
    pub fn of(world: &World, id: BodyId, scenery: bool) -> Option<Self> {
        let body = world.bodies().get(id.index())?;
        let (mut contacts, mut penetration) = (0, 0.0f32);
        for c in world.contacts().filter(|c| c.involves(id) && c.touching()) {
            contacts += 1;
            penetration = penetration.max(c.penetration());
        }
        let state = match (body.is_static(), scenery, body.is_sleeping()) {
            (true, true, _) => BodyState::Scenery,
            (true, false, _) => BodyState::Frozen,
            (false, _, true) => BodyState::Asleep,
            (false, _, false) => BodyState::Awake,
        };
        Some(Self {
            id,
            shape: *body.shape(),
            mass: body.mass(),
            inertia: body.inertia_local(),
            position: body.pose().position,
            velocity: body.linear_velocity(),
            angular_velocity: body.angular_velocity(),
            kinetic_energy: body.kinetic_energy(),
            contacts,
            penetration,
            state,
            name: None,
        })
    }
}

/// The whole world's figures.
#[derive(Clone, Debug, PartialEq)]
pub struct WorldReport {
    pub awake: usize,
    pub bodies: usize,
    /// Touching contact manifolds (body pairs), sleeping ones included.
    pub contacts: usize,
    pub islands: usize,
    /// J.
    pub kinetic_energy: f32,
    /// J, from the origin along gravity.
    pub potential_energy: f32,
    /// kg·m/s, world.
    pub momentum: Vec3,
    /// Deepest penetration among them, m (≥ 0).
    pub penetration: f32,
}

impl WorldReport {
    pub fn of(world: &World) -> Self {
        let (mut contacts, mut penetration) = (0, 0.0f32);
        for c in world.contacts().filter(|c| c.touching()) {
            contacts += 1;
            penetration = penetration.max(c.penetration());
        }
        Self {
            awake: world.awake_count(),
            bodies: world.len(),
            contacts,
            islands: world.island_count(),
            kinetic_energy: world.kinetic_energy(),
            potential_energy: world.potential_energy(),
            momentum: world.linear_momentum(),
            penetration,
        }
    }
}

/// One titled block of panel lines.
pub struct Section {
    pub title: String,
    pub lines: Vec<Line<'static>>,
}

impl Section {
    /// Rows it takes: a title row and its lines.
    fn height(&self) -> u16 {
        1 + self.lines.len() as u16
    }
}

/// A number with about 3 significant figures in at most `width` columns (≥ 5): "0.125", "12.50",
/// "1.2e4". Fewer decimals, then an exponent, when the number needs more room.
pub fn short_in(x: f32, width: usize) -> String {
    let a = x.abs();
    if !x.is_finite() {
        return format!("{x}");
    }
    if a == 0.0 {
        return "0".to_string();
    }
    let preferred: usize = if a >= 100.0 {
        1
    } else if a >= 1.0 {
        2
    } else {
        3
    };
    if a >= 1e-3 {
        if let Some(s) = (0..=preferred)
            .rev()
            .map(|decimals| format!("{x:.decimals$}"))
            .find(|s| s.chars().count() <= width)
        {
            return s;
        }
    }
    (0..=2)
        .rev()
        .map(|decimals| format!("{x:.decimals$e}"))
        .find(|s| s.chars().count() <= width)
        .unwrap_or_else(|| format!("{x:.0e}"))
}

/// [`short_in`] seven columns.
pub fn short(x: f32) -> String {
    short_in(x, 7)
}

/// A vector as three right-aligned short numbers of `width` columns each, one space apart.
pub fn short3_in(v: Vec3, width: usize) -> String {
    format!(
        "{:>width$} {:>width$} {:>width$}",
        short_in(v.x, width),
        short_in(v.y, width),
        short_in(v.z, width)
    )
}

/// [`short3_in`] seven columns a number.
pub fn short3(v: Vec3) -> String {
    short3_in(v, 7)
}

/// A length in the unit that reads best: "0.80 mm", "1.2 cm".
pub fn length(m: f32) -> String {
    if m < 0.01 {
        format!("{:.2} mm", m * 1e3)
    } else {
        format!("{} m", short(m))
    }
}

/// A row's label: up to 7 columns (longer ones push their value right), then a space.
fn label(text: &str) -> Span<'static> {
    Span::styled(format!("{text:<7} "), Style::default().fg(Color::Gray))
}

/// Columns a number gets in a vector row of a panel `inner_cols` wide: three numbers after an
/// 8-column label, at most 7 each.
pub fn number_cols(inner_cols: u16) -> usize {
    (usize::from(inner_cols).saturating_sub(10) / 3).clamp(5, 7)
}

fn row(name: &str, value: String) -> Line<'static> {
    Line::from(vec![label(name), Span::raw(value)])
}

/// The selected body's section (or how to select one), numbers `n` columns wide.
pub fn body_section(report: Option<&BodyReport>, n: usize) -> Section {
    let Some(r) = report else {
        return Section {
            title: "body".into(),
            lines: vec![Line::from("click a body to inspect it")],
        };
    };
    let (kind, size) = match r.shape {
        Shape::Cuboid { half_extents } => {
            let s = half_extents * 2.0;
            (
                "box",
                format!("{}×{}×{} m", short(s.x), short(s.y), short(s.z)),
            )
        }
        Shape::Sphere { radius } => ("sphere", format!("r {} m", short(radius))),
    };
    let state_color = match r.state {
        BodyState::Awake => Color::LightGreen,
        BodyState::Asleep => Color::LightBlue,
        BodyState::Frozen => Color::LightCyan,
        BodyState::Scenery => Color::Gray,
    };
    Section {
        title: match &r.name {
            Some(name) => format!("{name} ({kind} #{})", r.id.0),
            None => format!("{kind} #{}", r.id.0),
        },
        lines: vec![
            Line::from(vec![
                label("state"),
                Span::styled(r.state.name(), Style::default().fg(state_color)),
            ]),
            row("size", size),
            row("mass", format!("{} kg", short(r.mass))),
            row("I kg·m²", short3_in(r.inertia, n)),
            row("pos m", short3_in(r.position, n)),
            row("vel m/s", short3_in(r.velocity, n)),
            row("speed", format!("{} m/s", short(r.velocity.length()))),
            row("ω rad/s", short3_in(r.angular_velocity, n)),
            row("KE", format!("{} J", short(r.kinetic_energy))),
            row("touches", r.contacts.to_string()),
            row("depth", length(r.penetration)),
        ],
    }
}

/// The selected body lists at most this many joints (a hub of many shows the first and a count).
pub const MAX_JOINTS_LISTED: usize = 6;

/// The selected body's joints, a panel `inner_cols` wide: per joint a line with its kind, its other
/// end and the force on the body, and for the kinds that hold a torque a second line with it (and
/// the motor's and limits' axial part, `ax`, when it has them).
pub fn joints_section(joints: &[JointReport], inner_cols: usize) -> Section {
    let mut lines = Vec::new();
    for j in joints.iter().take(MAX_JOINTS_LISTED) {
        let force = format!(" {} N", short(j.force));
        let room = inner_cols.saturating_sub(force.chars().count() + j.kind.len() + 1);
        let other: String = j.other.chars().take(room).collect();
        let pad = room - other.chars().count();
        lines.push(Line::from(vec![
            Span::styled(format!("{} ", j.kind), Style::default().fg(Color::Gray)),
            Span::raw(format!("{other}{:pad$}{force}", "")),
        ]));
        let mut second = String::new();
        if let Some(t) = j.torque {
            second.push_str(&format!(" τ {} N·m", short_in(t, 6)));
        }
        if let Some(a) = j.axial {
            let unit = if j.axial_is_torque { "N·m" } else { "N" };
            second.push_str(&format!("  ax {} {unit}", short_in(a, 6)));
        }
        if !second.is_empty() {
            lines.push(Line::from(second));
        }
    }
    if joints.len() > MAX_JOINTS_LISTED {
        lines.push(Line::from(format!(
            "+ {} more",
            joints.len() - MAX_JOINTS_LISTED
        )));
    }
    Section {
        title: format!("joints ({})", joints.len()),
        lines,
    }
}

/// The world's section, numbers `n` columns wide.
pub fn world_section(r: &WorldReport, n: usize) -> Section {
    Section {
        title: "world".into(),
        lines: vec![
            row("awake", format!("{}/{}", r.awake, r.bodies)),
            row("contacts", r.contacts.to_string()),
            row("islands", r.islands.to_string()),
            row("KE", format!("{} J", short(r.kinetic_energy))),
            row("PE", format!("{} J", short(r.potential_energy))),
            row("Σmv", short3_in(r.momentum, n)),
            row("depth", length(r.penetration)),
        ],
    }
}

/// The panel: sections top to bottom, each drawn only if it fits whole.
pub struct InspectorPanel<'a> {
    pub sections: &'a [Section],
    /// Charted in the rows the sections leave (see [`Charts`]).
    pub history: Option<&'a History>,
}

impl Widget for InspectorPanel<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let block = Block::default()
            .borders(Borders::LEFT)
            .border_style(Style::default().fg(Color::DarkGray))
            .style(Style::default().bg(Color::Black).fg(Color::White));
        let inner = block.inner(area);
        block.render(area, buf);
        let title_style = Style::default()
            .fg(Color::Yellow)
            .add_modifier(Modifier::BOLD);
        let mut lines: Vec<Line> = Vec::new();
        for section in self.sections {
            if lines.len() as u16 + section.height() > inner.height {
                break;
            }
            lines.push(Line::from(Span::styled(
                format!(" {} ", section.title),
                title_style,
            )));
            lines.extend(section.lines.iter().cloned());
        }
        let used = lines.len() as u16;
        Paragraph::new(lines).render(inner, buf);
        if let Some(history) = self.history {
            let rest = Rect {
                y: inner.y + used,
                height: inner.height - used,
                ..inner
            };
            Charts { history }.render(rest, buf);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_numbers_fit_seven_columns() {
        for x in [
            0.0, 0.0004, -0.125, 2.71, -12.5, 999.9, 12345.0, -1e-7, 6.02e23, -1e-30,
        ] {
            assert!(short(x).chars().count() <= 7, "{x} → {}", short(x));
        }
        assert_eq!(short(0.125), "0.125");
        assert_eq!(short(-12.5), "-12.50");
        assert_eq!(short(250.0), "250.0");
        assert_eq!(length(0.0008), "0.80 mm");
    }

    #[test]
    fn the_panel_needs_room_for_the_scene_beside_it() {
        assert_eq!(panel_cols(200), WIDE_PANEL_COLS);
        assert_eq!(panel_cols(80), NARROW_PANEL_COLS);
        assert_eq!(panel_cols(NARROW_PANEL_COLS + MIN_SCENE_COLS - 1), 0);
        // A vector row fits inside either panel's border.
        for cols in [WIDE_PANEL_COLS, NARROW_PANEL_COLS] {
            let n = number_cols(cols - 1);
            let row = short3_in(glam::Vec3::splat(-1234.5678), n);
            assert!(
                8 + row.chars().count() <= usize::from(cols - 1),
                "{cols}: {row}"
            );
        }
    }

    #[test]
    fn a_joint_fits_the_narrow_panel_in_two_lines_and_a_hub_shows_a_count() {
        let hinge = |force: f32| JointReport {
            kind: "distance",
            other: "a body with a very long name".into(),
            force,
            torque: Some(-12345.678),
            axial: Some(-0.000123),
            axial_is_torque: true,
        };
        let inner = usize::from(NARROW_PANEL_COLS - 1);
        let joints: Vec<_> = (0..8).map(|i| hinge(1.5e6 * i as f32)).collect();
        let section = joints_section(&joints, inner);
        assert_eq!(section.title, "joints (8)");
        assert_eq!(section.lines.len(), 2 * MAX_JOINTS_LISTED + 1);
        for line in &section.lines {
            assert!(line.width() <= inner, "{line:?}");
        }
        assert_eq!(section.lines[0].to_string().chars().count(), inner);
        assert!(section.lines[2].to_string().ends_with(" 1500000 N"));
        assert_eq!(section.lines.last().unwrap().to_string(), "+ 2 more");
    }

    #[test]
    fn sections_that_do_not_fit_whole_are_left_out() {
        let sections = [
            Section {
                title: "a".into(),
                lines: vec![Line::from("one"), Line::from("two")],
            },
            Section {
                title: "b".into(),
                lines: vec![Line::from("three"), Line::from("four")],
            },
        ];
        let area = Rect::new(0, 0, 20, 5);
        let mut buf = Buffer::empty(area);
        InspectorPanel {
            sections: &sections,
            history: None,
        }
        .render(area, &mut buf);
        let text: String = (0..5)
            .map(|y| (0..20).map(|x| buf[(x, y)].symbol()).collect::<String>() + "\n")
            .collect();
        assert!(text.contains("two") && !text.contains(" b ") && !text.contains("three"));
    }
}
