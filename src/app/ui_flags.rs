//! The sandbox's switches: what the user has turned on or off from the keyboard, kept in one place so
//! that a new switch is a field here, not another loose flag on `App`. The fields are private: a
//! switch changes only through the methods here, so each way it can change is named in one file.

use super::input::leaving::Leave;

/// The user's on/off switches; each shows in the status bar or on screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UiFlags {
    /// Space: the world is not stepped...
    paused: bool,
    /// ...except once more after `.`.
    single_step: bool,
    /// `g`: gravity is on.
    gravity_on: bool,
    /// `x`: the strong hand (Shift does the same for one click).
    strong: bool,
    /// `h`: the left button grabs and drags instead of pushing (see `grab`).
    grab_mode: bool,
    /// `f` was pressed: the next click freezes/unfreezes instead of pushing.
    freeze_armed: bool,
    /// The last key asked to leave a changed world (see `leaving`): the same key again leaves.
    leave_asked: Option<Leave>,
}

impl Default for UiFlags {
    /// Running, with gravity, a gentle hand that pushes.
    fn default() -> Self {
        Self::new(true)
    }
}

impl UiFlags {
    /// Running, a gentle hand that pushes, and gravity on or off as the scene has it (a scene saved
    /// with it off starts with it off, so `g` turns it on rather than "on" to nothing).
    pub fn new(gravity_on: bool) -> Self {
        Self {
            paused: false,
            single_step: false,
            gravity_on,
            strong: false,
            grab_mode: false,
            freeze_armed: false,
            leave_asked: None,
        }
    }

    pub fn paused(&self) -> bool {
        self.paused
    }

    pub fn gravity_on(&self) -> bool {
        self.gravity_on
    }

    pub fn strong(&self) -> bool {
        self.strong
    }

    pub fn grab_mode(&self) -> bool {
        self.grab_mode
    }

    pub fn freeze_armed(&self) -> bool {
        self.freeze_armed
    }

    /// Space: pauses or runs; whether it is paused now.
    pub fn toggle_pause(&mut self) -> bool {
        self.paused = !self.paused;
        self.paused
    }

    /// Stops the world (a jump in time, the end of a replay).
    pub fn pause(&mut self) {
        self.paused = true;
    }

    /// `.`: pauses and lets one step through.
    pub fn step_once(&mut self) {
        self.paused = true;
        self.single_step = true;
    }

    /// Whether `.` let a step through since the last call.
    pub fn take_single_step(&mut self) -> bool {
        std::mem::take(&mut self.single_step)
    }

    /// `g`: gravity on or off; whether it is on now.
    pub fn toggle_gravity(&mut self) -> bool {
        self.gravity_on = !self.gravity_on;
        self.gravity_on
    }

    /// After a jump in time: the flag follows the world's gravity.
    pub fn set_gravity_on(&mut self, on: bool) {
        self.gravity_on = on;
    }

    /// `x`: the strong hand on or off; whether it is on now.
    pub fn toggle_strong(&mut self) -> bool {
        self.strong = !self.strong;
        self.strong
    }

    /// `h`: grab mode on or off; whether it is on now.
    pub fn toggle_grab_mode(&mut self) -> bool {
        self.grab_mode = !self.grab_mode;
        self.grab_mode
    }

    /// `f`: the next click freezes or unfreezes.
    pub fn arm_freeze(&mut self) {
        self.freeze_armed = true;
    }

    /// Whether `f` was waiting for a click; it waits no more.
    pub fn take_freeze_armed(&mut self) -> bool {
        std::mem::take(&mut self.freeze_armed)
    }

    /// A key asked to leave a changed world: the same key next leaves.
    pub fn ask_leave(&mut self, leave: Leave) {
        self.leave_asked = Some(leave);
    }

    /// The request to leave the previous input made, if any; it stands for one input only.
    pub fn take_leave_asked(&mut self) -> Option<Leave> {
        self.leave_asked.take()
    }

    /// What another scene keeps of the user's choices: the hand's strength and mode, and the pause.
    pub fn carry_to(&self, next: &mut UiFlags) {
        next.strong = self.strong;
        next.grab_mode = self.grab_mode;
        next.paused = self.paused;
    }
}
