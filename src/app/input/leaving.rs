//! Leaving a world: quitting, or switching to another scene. A world the user changed (spawned,
//! resized, froze, pushed, any input the world was given) and has not saved is not lost to one key:
//! the first press asks, a second press of the same key leaves, any other key changes the mind.
//! We ask rather than keep a recovery file: the answer is on the screen when it matters, and nothing
//! is written to a disk the user did not ask to write to.

use crate::app::App;

/// Where the user is going.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Leave {
    /// `q` or Esc with nothing open to close.
    Quit,
    /// `n` (forward) or `N`.
    Scene { forward: bool },
}

impl App {
    /// Takes the inputs the keys gave the world since the last step into the timeline; a world
    /// given any input has changed since it was loaded or saved.
    pub(crate) fn absorb_inputs(&mut self) {
        if self.timeline.absorb(&mut self.world) > 0 {
            self.unsaved = true;
        }
    }

    /// Whether the world has changed since it was loaded or last saved.
    pub fn has_unsaved_changes(&mut self) -> bool {
        self.absorb_inputs();
        self.unsaved
    }

    /// Leaves at once if nothing would be lost or this key asked already (`armed`, the request the
    /// previous key made); otherwise asks, naming the `key` pressed.
    pub(crate) fn leave(&mut self, leave: Leave, armed: Option<Leave>, key: &str) {
        // A replay's world is the recording's: nothing the user made is lost by leaving it.
        if armed == Some(leave) || self.replay.is_some() || !self.has_unsaved_changes() {
            match leave {
                Leave::Quit => self.quit = true,
                Leave::Scene { forward } => self.cycle_scene(forward),
            }
            return;
        }
        self.ui.ask_leave(leave);
        let verb = match leave {
            Leave::Quit => "quit",
            Leave::Scene { .. } => "switch scenes",
        };
        self.say(format!(
            "unsaved world: {key} again to {verb} · Ctrl+S saves"
        ));
    }
}
