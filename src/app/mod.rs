//! The interactive sandbox, headless: state, input, time and drawing. Only [`run`] touches a real
//! terminal; everything else runs against ratatui `Buffer`s and synthetic crossterm events, so tests
//! drive the app exactly as a person would.
//!
//! Each frame: drain input → run due physics steps (the hand's force applied before each) → draw.
//!
//! The folders group the app by what it does: [`input`] turns keys and the mouse into actions and
//! hands, [`panels`] draws the view, the status bar and what opens over it, [`time`] keeps the
//! clock, the timeline, rewinds, recordings and saves, and [`world`] makes the sandbox's own changes
//! to the bodies. The state each part needs is its own type with its own methods ([`ui_flags`],
//! [`input::hand::Hand`], [`input::selection::Selection`], [`panels::camera_home::CameraView`],
//! [`time::timeline::Timeline`], [`panels::debug_views::DebugViews`],
//! [`panels::help_state::HelpState`]); `App` holds them.

pub mod byte_budget;
pub mod input;
pub mod panels;
pub mod run;
pub mod snapshot;
pub mod time;
pub mod ui_flags;
pub mod world;

use std::time::Duration;

use glam::Vec3;
use ratatui::layout::Rect;

use crate::app::input::picking::ScreenView;
use crate::geometry::{Camera, CellPixels, Projection, Viewport};
use crate::physics::World;
use crate::render::{Drawable, Frame, RenderMode, RenderOptions, Renderer};
use crate::scene::Scene;
use crate::term::{CellMode, ColorDepth, Dither, guessed_hint};

use byte_budget::ByteBudget;
use input::colour_probe;
use input::hand::Hand;
use input::selection::Selection;
use panels::camera_home::CameraView;
use panels::debug_views;
use panels::look::BodyLook;
use panels::status::Stats;
use panels::view;
use time::clock::StepClock;
use time::{rewind, timeline};
use world::{grow, lost};

/// At most this many physics steps per frame; more real time than that is dropped (no spiral).
pub const MAX_STEPS_PER_FRAME: u32 = 8;
/// Field of view used when switching from orthographic back to perspective, radians.
pub const DEFAULT_FOV_Y: f32 = 70.0 * std::f32::consts::PI / 180.0;

/// Settings the app starts with (from the command line and the terminal).
#[derive(Clone, Debug)]
pub struct AppConfig {
    pub color_depth: ColorDepth,
    /// False when the depth was a guess (ssh drops COLORTERM); the status bar then says how to switch.
    pub color_depth_certain: bool,
    /// How colours the palette lacks are shown at 256 and 16 colours.
    pub dither: Dither,
    /// Ask the terminal whether it does truecolor before the first frame (see `term::probe`): set
    /// when the depth is a guess.
    pub probe_truecolor: bool,
    /// Terminal cell height / width.
    pub cell_aspect: f32,
    /// Neither `--cell-aspect` nor the pty gave the cell aspect (xterm.js reports no pixel size):
    /// ask the terminal for its cell size in pixels before the first frame (see `term::probe`).
    pub ask_cell_size: bool,
    /// Highlight the body under the pointer as it moves (needs all-motion mouse reporting).
    pub hover: bool,
    /// Render at 2× and average.
    pub supersample: bool,
    /// How many pixels a terminal cell shows, and with which glyphs (`--cells`; a key cycles it).
    pub cells: CellMode,
    /// Most bytes per second sent to the terminal (0 = no limit); see [`byte_budget`].
    pub max_bytes_per_second: u64,
    /// Why that limit: the link (SSH or local) or the flag; the status bar names it when it holds
    /// frames.
    pub byte_limit_origin: byte_budget::LimitOrigin,
    /// Where Ctrl+S writes the world (`None`: the working directory); see [`time::save`].
    pub save_dir: Option<std::path::PathBuf>,
}

/// The byte budget headless apps get by default: the SSH link's (the strictest default, so tests see
/// frames held); the terminal app picks one by its link (see [`byte_budget::LimitOrigin`]).
pub const DEFAULT_MAX_BYTES_PER_SECOND: u64 = byte_budget::SSH_MAX_BYTES_PER_SECOND;

impl Default for AppConfig {
    fn default() -> Self {
        Self {
            color_depth: ColorDepth::TrueColor,
            color_depth_certain: true,
            dither: Dither::Ordered,
            probe_truecolor: false,
            cell_aspect: 2.0,
            ask_cell_size: false,
            hover: false,
            supersample: true,
            cells: CellMode::Half,
            max_bytes_per_second: DEFAULT_MAX_BYTES_PER_SECOND,
            byte_limit_origin: byte_budget::LimitOrigin::Ssh,
            save_dir: None,
        }
    }
}

/// The sandbox. Its state is private to `app` and the modules that own each part; the few
/// `pub(crate)` fields (the world, the camera, the renderer and its frame) are what `bench` measures.
pub struct App {
    scene: Scene,
    pub(crate) world: World,
    looks: Vec<BodyLook>,
    /// The camera the view is seen through (see [`panels::camera_home`]).
    pub(crate) camera: CameraView,
    pub(crate) config: AppConfig,
    pub(crate) renderer: Renderer,
    pub(crate) frame: Frame,
    pub(crate) drawables: Vec<Drawable>,
    pub(crate) render_options: RenderOptions,
    clock: StepClock,
    hand: Hand,
    /// Terminal area the app was last laid out for.
    area: Rect,
    /// The pointer, the body under it and the body picked (see [`input::selection`]).
    selection: Selection,
    /// Pause, gravity, the strong hand, grabbing, an armed freeze (see [`ui_flags`]).
    ui: ui_flags::UiFlags,
    /// The help overlay, open or not (see [`panels::help_state`]).
    help: panels::help_state::HelpState,
    quit: bool,
    /// The world was given an input since it was loaded or last saved (see [`input::leaving`]).
    unsaved: bool,
    /// Something changed that the screen does not show yet.
    dirty: bool,
    /// The last frame drawn showed something moving: when the world comes to rest, one more frame
    /// replaces its rates with "idle" (and then nothing is written until something changes).
    last_frame_active: bool,
    message: String,
    stats: Stats,
    /// Bytes the terminal may still be sent (frames are skipped while it is overdrawn).
    pub(crate) byte_budget: ByteBudget,
    /// Dynamic bodies below this height fell off the world and are frozen (see [`lost`]).
    lost_below: Option<f32>,
    /// Every input the world was given, keyframes to rewind through, the recording (see [`timeline`]).
    timeline: timeline::Timeline,
    /// Set when replaying a recording: its camera changes, and input that would change the world is
    /// ignored (see [`rewind`]).
    replay: Option<rewind::ReplayView>,
    /// A body growing or shrinking over the next few steps (see [`grow`]).
    growth: Option<grow::Growth>,
    /// Overlays, the inspector and live settings (see [`debug_views`]).
    inspect: debug_views::DebugViews,
    /// Ctrl+L: the terminal is to be cleared and every cell written again.
    repaint: bool,
    /// Drops terminal replies to the truecolor probe that arrive late (see [`colour_probe`]).
    late_replies: colour_probe::LateReplies,
}

impl App {
    pub fn new(scene: Scene, config: AppConfig) -> Self {
        let mut world = scene.build_world();
        let timeline =
            timeline::Timeline::new(scene.bodies.iter().map(|b| b.desc).collect(), &mut world);
        let looks = BodyLook::of_scene(&scene);
        let render_options = RenderOptions {
            supersample: config.supersample,
            ..RenderOptions::default()
        };
        let byte_budget = ByteBudget::new(config.max_bytes_per_second);
        let lost_below = lost::lost_below(&scene);
        // A scene without gravity (one saved while it was off, or a space scene) starts with it
        // off, so `g` turns it on rather than "on" to nothing.
        let ui = ui_flags::UiFlags::new(scene.settings.gravity != glam::Vec3::ZERO);
        let message = if config.color_depth_certain {
            "? for help".to_string()
        } else {
            format!("{} · ? for help", guessed_hint(config.color_depth))
        };
        Self {
            camera: CameraView::new(scene.camera),
            clock: StepClock::new(scene.settings.dt, MAX_STEPS_PER_FRAME),
            scene,
            world,
            looks,
            config,
            renderer: Renderer::new(),
            frame: Frame::new(0, 0),
            drawables: Vec::new(),
            render_options,
            hand: Hand::default(),
            area: Rect::default(),
            selection: Selection::default(),
            ui,
            help: panels::help_state::HelpState::default(),
            quit: false,
            unsaved: false,
            dirty: true,
            last_frame_active: false,
            message,
            stats: Stats::default(),
            byte_budget,
            lost_below,
            timeline,
            replay: None,
            growth: None,
            inspect: debug_views::DebugViews::default(),
            repaint: false,
            late_replies: colour_probe::LateReplies::default(),
        }
    }

    pub fn world(&self) -> &World {
        &self.world
    }

    /// The world, for tests and benchmarks that act on it directly.
    pub fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    pub fn camera(&self) -> &Camera {
        self.camera.get()
    }

    pub fn camera_mut(&mut self) -> &mut Camera {
        self.dirty = true;
        self.camera.get_mut()
    }

    pub fn render_mode(&self) -> RenderMode {
        self.render_options.mode
    }

    pub fn should_quit(&self) -> bool {
        self.quit
    }

    pub fn message(&self) -> &str {
        &self.message
    }

    pub fn is_paused(&self) -> bool {
        self.ui.paused()
    }

    /// The last rendered pixel frame (colour, depth and id buffers).
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// Whether the next frame would show anything new: bodies moving, input, a resize, a message.
    pub fn needs_redraw(&self) -> bool {
        self.dirty
            || (!self.ui.paused() && self.world.awake_count() > 0)
            || self.hand.is_active()
            || self.growth.is_some()
    }

    /// Ctrl+L: asks the event loop to clear the terminal and write every cell again (after another
    /// program scribbled on it).
    pub(crate) fn request_repaint(&mut self) {
        self.repaint = true;
        self.dirty = true;
    }

    /// Whether a full repaint was asked for since the last call.
    pub fn take_repaint(&mut self) -> bool {
        std::mem::take(&mut self.repaint)
    }

    /// Lays the app out for a terminal of `area` (viewport above a one-line status bar).
    pub fn resize(&mut self, area: Rect) {
        if area != self.area {
            self.area = area;
            self.dirty = true;
        }
    }

    /// The 3D view's cells: the whole terminal but the last row, and but the inspector panel when
    /// it is open.
    pub fn viewport_area(&self) -> Rect {
        self.beside_panel(view::viewport_area(self.area))
    }

    /// The 3D view as the terminal shows it, for the hand and the grab (see [`ScreenView`]).
    pub fn screen_view(&self) -> ScreenView {
        ScreenView {
            camera: *self.camera.get(),
            viewport: self.viewport(),
            cells: self.viewport_area(),
            samples: if self.view_render_options().supersample {
                2
            } else {
                1
            },
        }
    }

    /// The pixel grid of the 3D view: the cell mode's pixels per cell (one column and two rows for
    /// half blocks), for drawing and picking alike.
    pub fn viewport(&self) -> Viewport {
        let cells = self.viewport_area();
        let (cols, rows) = self.config.cells.pixels_per_cell();
        Viewport::of_cells(
            cells.width,
            cells.height,
            CellPixels { cols, rows },
            self.config.cell_aspect,
        )
    }

    /// Advances real time: runs the physics steps that are due (none while paused, one after `.`).
    pub fn advance(&mut self, elapsed: Duration) {
        let steps = if self.ui.paused() {
            self.clock.reset();
            u32::from(self.ui.take_single_step())
        } else {
            // The time scale (live settings) runs simulated time slower or faster than real time.
            self.clock.advance(elapsed.mul_f32(self.time_scale()))
        };
        for _ in 0..steps {
            self.step_physics();
        }
    }

    /// One physics step, with the hand's push, pull or grab applied first.
    pub fn step_physics(&mut self) {
        let start = std::time::Instant::now();
        // Inputs reach the world only here, between steps: what the keys did since the last step,
        // then a rewound timeline's inputs due now, then the hand's (see `timeline`).
        self.absorb_inputs();
        self.timeline.apply_due(&mut self.world);
        self.before_step_view();
        self.grow_step();
        self.apply_hand();
        self.absorb_inputs();
        self.world.step();
        self.timeline.after_step(&self.world);
        let over = self.world.pairs_over_cap();
        if over > 0 {
            self.say(format!(
                "too many bodies in one place: {over} contacts ignored"
            ));
        }
        // A rewound timeline already holds the freezes of bodies that fell off.
        if let Some(height) = self.lost_below
            && self.timeline.rewound_steps(&self.world) == 0
            && let Some(id) = lost::freeze_lost(&mut self.world, height)
        {
            // The world froze it, not the user: taken now, it does not count as a change to save.
            self.timeline.absorb(&mut self.world);
            let name = self.body_name(id);
            self.say(format!(
                "{name} fell off the world and is frozen (r resets)"
            ));
        }
        let step_ms = start.elapsed().as_secs_f64() * 1e3;
        self.stats.record_physics(step_ms);
        self.after_step_inspection(step_ms);
        if self.world.awake_count() > 0 {
            self.dirty = true;
        }
    }

    /// Puts every body back where the scene put it.
    pub fn reset(&mut self) {
        let bodies: Vec<_> = self.scene.bodies.iter().map(|b| b.desc).collect();
        self.world.reset_bodies(&bodies);
        self.looks.truncate(self.scene.bodies.len());
        self.hand = Hand::default();
        self.selection.clear_bodies();
        self.clock.reset();
        // Say what the reset kept, so a scene hanging in mid-air does not look broken.
        let mut message = String::from("bodies reset");
        if !self.ui.gravity_on() {
            message.push_str(" · gravity still off (g)");
        }
        if !self.camera_is_home() {
            message.push_str(" · camera kept (c resets it)");
        }
        self.say(message);
    }

    pub(crate) fn say(&mut self, message: impl Into<String>) {
        self.message = message.into();
        self.dirty = true;
    }

    pub(crate) fn toggle_gravity(&mut self) {
        let on = self.ui.toggle_gravity();
        let gravity = if on {
            self.gravity_vector()
        } else {
            Vec3::ZERO
        };
        self.world.set_gravity(gravity);
        self.say(if on { "gravity on" } else { "gravity off" });
    }

    pub(crate) fn toggle_projection(&mut self) {
        let name = match self.camera.toggle_projection() {
            Projection::Perspective { .. } => "perspective",
            Projection::Orthographic { .. } => "orthographic",
        };
        self.say(name);
    }
}
