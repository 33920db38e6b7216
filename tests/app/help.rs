//! The help overlay at any size (issue 28): at 40×12 it showed 9 of its 21 rows, the actions cut to
//! four characters, with no way to scroll; and its widest row touched the left border.

use crate::common;

use common::app::{app_on, char_key, key, screen};
use crossterm::event::{Event, KeyCode, KeyModifiers, MouseEvent, MouseEventKind};
use nudge::app::input::CONTROLS;

/// The text inside the help box's borders, row by row, trimmed.
fn help_rows(screen: &[String]) -> Vec<String> {
    screen
        .iter()
        .filter_map(|row| {
            let start = row.find('│')?;
            let rest = &row[start + '│'.len_utf8()..];
            let end = rest.rfind('│')?;
            Some(rest[..end].trim().to_string())
        })
        .collect()
}

#[test]
fn at_40_by_12_the_help_scrolls_through_every_control_uncut_and_other_keys_close_it() {
    let (cols, rows) = (40, 12);
    let mut app = app_on("default", cols, rows);
    app.handle_event(&char_key('?'));
    let first = screen(&mut app, cols, rows);
    assert!(first[0..2].concat().contains("↑↓ 1-"), "{first:#?}");
    let mut seen = String::new();
    for _ in 0..80 {
        let shown = screen(&mut app, cols, rows);
        seen.push_str(&help_rows(&shown).join(" "));
        seen.push(' ');
        app.handle_event(&key(KeyCode::Down));
    }
    // Every control's keys and every word of its action, somewhere in the scrolled rows.
    for (keys, action) in CONTROLS {
        assert!(seen.contains(keys), "{keys} never shown");
        for word in action.split(' ') {
            assert!(seen.contains(word), "{word} of '{action}' never shown");
        }
    }
    let last = CONTROLS.last().unwrap().1;
    assert!(
        help_rows(&screen(&mut app, cols, rows))
            .join(" ")
            .contains(last),
        "scrolled to the end"
    );
    // PageUp goes back, the wheel too; still open.
    let end = screen(&mut app, cols, rows);
    app.handle_event(&key(KeyCode::PageUp));
    assert_ne!(screen(&mut app, cols, rows), end);
    for _ in 0..20 {
        app.handle_event(&Event::Mouse(MouseEvent {
            kind: MouseEventKind::ScrollUp,
            column: 20,
            row: 5,
            modifiers: KeyModifiers::NONE,
        }));
    }
    let top = screen(&mut app, cols, rows);
    assert!(
        help_rows(&top).join(" ").contains(CONTROLS[0].0),
        "{top:#?}"
    );
    // Any other key closes it, and does nothing else.
    app.handle_event(&char_key('q'));
    assert!(!app.should_quit());
    assert!(!screen(&mut app, cols, rows).concat().contains("↑↓"));
    assert_eq!(app.message(), "help closed");
}

#[test]
fn where_the_help_fits_the_arrows_close_it_and_no_row_touches_the_border() {
    let (cols, rows) = (120, 40);
    let mut app = app_on("default", cols, rows);
    app.handle_event(&key(KeyCode::F(1)));
    let shown = screen(&mut app, cols, rows);
    let text = shown.concat();
    assert!(text.contains("any key closes"));
    for (keys, action) in CONTROLS {
        assert!(text.contains(&format!("{keys}  {action}")), "{keys}");
    }
    for row in &shown {
        if let Some(i) = row.find('│') {
            let after = row[i + '│'.len_utf8()..].chars().next();
            assert_eq!(after, Some(' '), "touches the border: {row}");
        }
    }
    app.handle_event(&key(KeyCode::Down));
    assert!(
        !screen(&mut app, cols, rows)
            .concat()
            .contains("any key closes")
    );
}
