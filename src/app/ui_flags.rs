//! The sandbox's switches: what the user has turned on or off from the keyboard, kept in one place so
//! that a new switch is a field here, not another loose flag on `App`.

/// The user's on/off switches; each shows in the status bar or on screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UiFlags {
    /// Space: the world is not stepped...
    pub paused: bool,
    /// ...except once more after `.`.
    pub single_step: bool,
    /// `g`: gravity is on.
    pub gravity_on: bool,
    /// `x`: the strong hand (Shift does the same for one click).
    pub strong: bool,
    /// `h`: the left button grabs and drags instead of pushing (see `grab`).
    pub grab_mode: bool,
    /// `f` was pressed: the next click freezes/unfreezes instead of pushing.
    pub freeze_armed: bool,
    /// The last key asked to leave a changed world (see `leaving`): the same key again leaves.
    pub leave_asked: Option<super::input::leaving::Leave>,
}

impl Default for UiFlags {
    /// Running, with gravity, a gentle hand that pushes.
    fn default() -> Self {
        Self {
            paused: false,
            single_step: false,
            gravity_on: true,
            strong: false,
            grab_mode: false,
            freeze_armed: false,
            leave_asked: None,
        }
    }
}
