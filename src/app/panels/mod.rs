//! What the sandbox shows: the 3D view and how each body looks, the status bar and the names it
//! gives bodies, the camera's framing, and the panels drawn over or beside the view (help,
//! inspector, debug overlays and their menu, live settings, charts, profile). Each module owns its
//! piece of screen; none of them changes the world.

pub mod camera_home;
pub mod charts;
pub mod debug_views;
pub mod help;
pub mod help_state;
pub mod inspector;
pub mod joint_view;
pub mod live_settings;
pub mod look;
pub mod mass_text;
pub mod names;
pub mod overlays;
pub mod profile;
pub mod status;
pub mod view;
