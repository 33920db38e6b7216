//! The event loop on a real terminal, and the frame presenter it shares with the tests.

use std::io::{self, Write};
use std::time::{Duration, Instant};

use crossterm::event::{self, Event, KeyEventKind};
use crossterm::terminal::{BeginSynchronizedUpdate, EndSynchronizedUpdate};
use ratatui::backend::CrosstermBackend;
use ratatui::layout::Rect;
use ratatui::{Terminal, TerminalOptions};

use super::{App, AppConfig};
use crate::scene::Scene;
use crate::term::probe::{Answer, ProbeOutcome, Questions};
#[cfg(unix)]
use crate::term::probe::{PROBE_TIMEOUT, StdinReplies, ask};
use crate::term::{
    ByteCounter, CountingWriter, EndedBySignal, SignalRequest, Signals, TerminalGuard,
};

/// How long the loop sleeps waiting for input when nothing moves.
const IDLE_WAIT: Duration = Duration::from_millis(250);
/// How long a hang-up leaves the loop to quit on its own before the process exits: two idle waits.
const HANGUP_GRACE: Duration = IDLE_WAIT.saturating_mul(2);

/// A terminal that counts what it is sent: ratatui's diffing backend over a byte-counting writer.
pub struct Screen<W: Write> {
    terminal: Terminal<CrosstermBackend<CountingWriter<W>>>,
    counter: ByteCounter,
    /// The area of the last frame drawn (`None` before the first): a frame of another area repaints
    /// every cell.
    last_area: Option<Rect>,
}

/// What one turn of the loop did to the terminal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Turn {
    /// A frame was drawn, costing this many bytes (0 if no cell changed).
    Drawn(u64),
    /// A frame was due but held back: the byte budget is overdrawn (see `app::byte_budget`).
    Held,
    /// Nothing moved: nothing was drawn.
    Idle,
}

impl Turn {
    /// Bytes written to the terminal.
    pub fn bytes(self) -> u64 {
        match self {
            Turn::Drawn(bytes) => bytes,
            Turn::Held | Turn::Idle => 0,
        }
    }
}

impl<W: Write> Screen<W> {
    /// A screen whose size follows the real terminal.
    pub fn new(writer: W) -> io::Result<Self> {
        let counter = ByteCounter::default();
        let backend = CrosstermBackend::new(CountingWriter::with_counter(writer, counter.clone()));
        Ok(Self {
            terminal: Terminal::new(backend)?,
            counter,
            last_area: None,
        })
    }

    /// A screen of fixed size (tests, benchmarks): never asks a terminal for its size.
    pub fn fixed(writer: W, area: Rect) -> io::Result<Self> {
        let counter = ByteCounter::default();
        let backend = CrosstermBackend::new(CountingWriter::with_counter(writer, counter.clone()));
        let options = TerminalOptions {
            viewport: ratatui::Viewport::Fixed(area),
        };
        Ok(Self {
            terminal: Terminal::with_options(backend, options)?,
            counter,
            last_area: None,
        })
    }

    /// Draws one frame: only the cells that changed, wrapped in a synchronized update (mode 2026) so
    /// the terminal shows it whole. Returns the bytes written. The frame is charged to the app's byte
    /// budget unless it repainted the whole screen (the first frame, or one after a resize).
    pub fn present(&mut self, app: &mut App) -> io::Result<u64> {
        let before = self.counter.get();
        let active = app.world.awake_count() > 0 || app.hand.is_active();
        app.stats.idle = !active;
        if !active && app.last_frame_active {
            app.came_to_rest();
        }
        let mut area = Rect::default();
        let start = Instant::now();
        let mut draw_ms = 0.0;
        crossterm::queue!(self.terminal.backend_mut(), BeginSynchronizedUpdate)?;
        self.terminal.draw(|frame| {
            area = frame.area();
            let draw_start = Instant::now();
            app.draw(area, frame.buffer_mut());
            draw_ms = draw_start.elapsed().as_secs_f64() * 1e3;
        })?;
        crossterm::queue!(self.terminal.backend_mut(), EndSynchronizedUpdate)?;
        self.terminal.backend_mut().flush()?;
        // The profile's terminal write: ratatui's diff, the escapes and the write, without drawing.
        let write_ms = start.elapsed().as_secs_f64() * 1e3 - draw_ms;
        app.inspect.frame_profile.write.record(write_ms);
        let bytes = self.counter.get() - before;
        if self.last_area == Some(area) {
            app.byte_budget.spend(bytes);
        }
        self.last_area = Some(area);
        app.stats.record_frame(Instant::now(), bytes);
        if !active {
            app.stats.rest();
        }
        app.last_frame_active = active;
        Ok(bytes)
    }

    /// Draws a frame if the app's byte budget allows one, else holds it back (the app stays due
    /// for a redraw, so the next allowed frame shows the latest state).
    pub fn present_within_budget(&mut self, app: &mut App) -> io::Result<Turn> {
        if app.take_repaint() {
            // Ctrl+L: forget what the terminal shows; the next frame writes every cell (uncharged,
            // as after a resize).
            self.terminal.clear()?;
            self.last_area = None;
        }
        if !app.byte_budget.may_draw() {
            app.stats.record_held(Instant::now());
            return Ok(Turn::Held);
        }
        self.present(app).map(Turn::Drawn)
    }

    /// Bytes written since the screen was made.
    pub fn bytes_written(&self) -> u64 {
        self.counter.get()
    }

    /// Clears the screen and forgets what it showed, so the next frame repaints every cell (and is
    /// not charged to the byte budget). Unlike ratatui's `Terminal::clear`, it never asks the
    /// terminal where its cursor is (`ESC[6n`): a terminal that does not answer would stall us
    /// for two seconds and then fail.
    pub fn repaint_all(&mut self) -> io::Result<()> {
        let size = self.terminal.size()?;
        self.terminal
            .resize(Rect::new(0, 0, size.width, size.height))?;
        self.last_area = None;
        Ok(())
    }

    pub fn terminal_mut(&mut self) -> &mut Terminal<CrosstermBackend<CountingWriter<W>>> {
        &mut self.terminal
    }
}

/// One turn of the loop after input, `elapsed` after the last: run the due physics, refill the byte
/// budget, then draw if anything changed and the budget allows (a scene at rest costs nothing).
pub fn tick<W: Write>(
    app: &mut App,
    screen: &mut Screen<W>,
    elapsed: Duration,
) -> io::Result<Turn> {
    app.advance(elapsed);
    app.timeline.flush_recording();
    app.byte_budget.refill(elapsed);
    if app.needs_redraw() || app.last_frame_active {
        // (After the world comes to rest, one last frame replaces the rates with "idle".)
        screen.present_within_budget(app)
    } else {
        app.stats.record_idle(Instant::now());
        Ok(Turn::Idle)
    }
}

/// Asks the terminal on stdin/stdout whether it does truecolor (see `term::probe`); an error or a
/// stdin that is not the terminal counts as no answer, with nothing left to come.
fn probe_terminal(questions: Questions) -> ProbeOutcome {
    let silent = ProbeOutcome {
        answer: Answer::Silent,
        cell_px: None,
        complete: true,
    };
    #[cfg(unix)]
    if std::io::IsTerminal::is_terminal(&io::stdin()) {
        let mut replies = StdinReplies(io::stdin());
        return ask(&mut io::stdout(), &mut replies, PROBE_TIMEOUT, questions).unwrap_or(
            ProbeOutcome {
                complete: false,
                ..silent
            },
        );
    }
    silent
}

/// Runs the sandbox on the real terminal until the user quits or a signal arrives. The terminal is
/// restored on every way out: return, error (guard `Drop`) and panic (the guard's hook).
pub fn run(scene: Scene, config: AppConfig, fps: u32) -> anyhow::Result<()> {
    run_app(App::new(scene, config), fps)
}

/// The event loop over an app already made (a sandbox, a replay); a recording is finished at the end.
/// A fatal signal ends it with [`EndedBySignal`] after the terminal is restored.
pub fn run_app(mut app: App, fps: u32) -> anyhow::Result<()> {
    let signals = Signals::install()?;
    crate::term::exit_after_hangup(HANGUP_GRACE)?;
    let mut guard = TerminalGuard::enter(app.config.hover)?;
    if app.config.probe_truecolor || app.config.ask_cell_size {
        // In raw mode, before the event loop reads anything.
        let outcome = probe_terminal(Questions {
            truecolor: app.config.probe_truecolor,
            cell_size: app.config.ask_cell_size,
        });
        app.apply_probe(outcome, Instant::now());
    }
    let mut screen = Screen::new(io::stdout())?;
    screen.repaint_all()?;
    let frame_time = Duration::from_secs_f64(1.0 / fps.clamp(1, 240) as f64);
    let mut last_tick = Instant::now();
    let mut last_frame = Instant::now() - frame_time;
    let mut ended_by = None;

    while !app.should_quit() {
        match signals.take() {
            Some(SignalRequest::Exit(signal)) => {
                ended_by = Some(signal);
                break;
            }
            Some(SignalRequest::Suspend) => {
                suspend(&mut app, &mut guard, &mut screen, &signals)?;
                continue;
            }
            Some(SignalRequest::Resume) => {
                resume(&mut app, &mut guard, &mut screen)?;
                continue;
            }
            None => {}
        }
        let wait = if app.needs_redraw() {
            frame_time.saturating_sub(last_frame.elapsed())
        } else {
            IDLE_WAIT
        };
        if event::poll(wait)? {
            // Drain everything that is queued so a click acts on the very next physics step.
            loop {
                let event = event::read()?;
                if is_suspend_key(&event) {
                    suspend(&mut app, &mut guard, &mut screen, &signals)?;
                    break;
                }
                app.handle_event(&event);
                if !event::poll(Duration::ZERO)? {
                    break;
                }
            }
        }
        if app.needs_redraw() && last_frame.elapsed() < frame_time {
            continue;
        }
        let now = Instant::now();
        let turn = tick(&mut app, &mut screen, now - last_tick)?;
        last_tick = now;
        if turn != Turn::Idle {
            // A held frame uses its slot too: the loop waits a frame time, not a busy spin.
            last_frame = now;
        }
    }
    drop(screen);
    guard.restore()?;
    app.finish_recording()?;
    match ended_by {
        Some(signal) => Err(EndedBySignal(signal).into()),
        None => Ok(()),
    }
}

/// Ctrl+Z: in raw mode the terminal sends it as a key instead of stopping us.
fn is_suspend_key(event: &Event) -> bool {
    matches!(
        event,
        Event::Key(key) if key.kind == KeyEventKind::Press
            && super::input::keys::action_of(key.code, key.modifiers)
                == Some(super::input::action::Action::Suspend)
    )
}

/// Job control: gives the terminal back, stops until continued (`fg`), then takes it again.
fn suspend<W: Write>(
    app: &mut App,
    guard: &mut TerminalGuard,
    screen: &mut Screen<W>,
    signals: &Signals,
) -> io::Result<()> {
    // The button comes up while the terminal is the shell's: whatever the hand holds, it lets go.
    app.release_hand();
    guard.suspend()?;
    crate::term::signals::stop_self()?;
    // Continued: SIGCONT's own request would only repeat what follows.
    signals.clear_resume();
    resume(app, guard, screen)
}

/// After a stop: raw mode, the alternate screen and mouse reporting again, laid out for the
/// terminal's current size (it may have changed meanwhile) and repainted whole.
fn resume<W: Write>(
    app: &mut App,
    guard: &mut TerminalGuard,
    screen: &mut Screen<W>,
) -> io::Result<()> {
    guard.resume()?;
    screen.repaint_all()?;
    let (cols, rows) = crossterm::terminal::size()?;
    app.handle_event(&Event::Resize(cols, rows));
    app.dirty = true;
    Ok(())
}
