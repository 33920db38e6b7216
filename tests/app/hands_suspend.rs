//! Ctrl+Z while a body is held, on a real pseudo-terminal (see `tests/pty/mod.rs`): the button
//! comes up while the shell has the terminal, where the sandbox cannot see it, so the hand lets go
//! as the sandbox stops; continued, it does not hold the body any more.
#![cfg(target_os = "linux")]

use crate::pty;

use nudge::app::{App, AppConfig};
use nudge::bench::hands::cell_of;
use nudge::physics::BodyId;
use pty::{Sandbox, TIMEOUT};
use ratatui::layout::Rect;

#[test]
fn ctrl_z_while_grabbing_lets_go() {
    // Where the default scene's box #1 is drawn on the sandbox's 100×30 terminal.
    let mut app = App::new(nudge::scene::load("default").unwrap(), AppConfig::default());
    app.resize(Rect::new(0, 0, 100, 30));
    let (col, row) = cell_of(&app, app.world().body(BodyId(1)).pose().position);
    let mut sandbox = Sandbox::start(&[]);
    sandbox.type_keys(b"h");
    // SGR mouse: the left button down at the box (1-based cells).
    sandbox.type_keys(format!("\x1b[<0;{};{}M", col + 1, row + 1).as_bytes());
    let pressed = sandbox.mark();
    assert!(
        sandbox.wait_for(b"box #1", pressed, TIMEOUT).is_some(),
        "grabbed: {:?}",
        sandbox.text()
    );
    let mark = sandbox.mark();
    sandbox.type_keys(b"\x1a");
    assert!(sandbox.wait_state(|s| s == 'T'), "the sandbox did not stop");
    sandbox.continue_job();
    let repainted = sandbox.wait_for(b"\x1b[?1049h", mark, TIMEOUT);
    let repainted = repainted.expect("back on the alternate screen");
    // Repainted whole, the status bar says the hand let go (or threw the box, if it still swung).
    let let_go = sandbox.wait_for(b"let go of box #1", repainted, TIMEOUT);
    let threw = sandbox.wait_for(b"threw box #1", repainted, std::time::Duration::ZERO);
    assert!(let_go.or(threw).is_some(), "{:?}", sandbox.text());
    // The grab changed the world: the first q asks, the second quits.
    let mark = sandbox.mark();
    sandbox.type_keys(b"q");
    assert!(
        sandbox.wait_for(b"again to quit", mark, TIMEOUT).is_some(),
        "{:?}",
        sandbox.text()
    );
    sandbox.type_keys(b"q");
    assert_eq!(sandbox.wait_exit(TIMEOUT), Some(0), "{:?}", sandbox.text());
}
