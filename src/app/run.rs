//! The event loop on a real terminal, and the frame presenter it shares with the tests.

use std::io::{self, Write};
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use crossterm::event;
use crossterm::terminal::{BeginSynchronizedUpdate, EndSynchronizedUpdate};
use ratatui::backend::CrosstermBackend;
use ratatui::layout::Rect;
use ratatui::{Terminal, TerminalOptions};

use super::{App, AppConfig};
use crate::scene::Scene;
use crate::term::{ByteCounter, CountingWriter, TerminalGuard};

/// How long the loop sleeps waiting for input when nothing moves.
const IDLE_WAIT: Duration = Duration::from_millis(250);

/// A terminal that counts what it is sent: ratatui's diffing backend over a byte-counting writer.
pub struct Screen<W: Write> {
    terminal: Terminal<CrosstermBackend<CountingWriter<W>>>,
    counter: ByteCounter,
}

impl<W: Write> Screen<W> {
    /// A screen whose size follows the real terminal.
    pub fn new(writer: W) -> io::Result<Self> {
        let counter = ByteCounter::default();
        let backend = CrosstermBackend::new(CountingWriter::with_counter(writer, counter.clone()));
        Ok(Self {
            terminal: Terminal::new(backend)?,
            counter,
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
        })
    }

    /// Draws one frame: only the cells that changed, wrapped in a synchronized update (mode 2026) so
    /// the terminal shows it whole. Returns the bytes written.
    pub fn present(&mut self, app: &mut App) -> io::Result<u64> {
        let before = self.counter.get();
        let active = app.world.awake_count() > 0 || app.hand.is_active();
        app.stats.idle = !active;
        crossterm::queue!(self.terminal.backend_mut(), BeginSynchronizedUpdate)?;
        self.terminal
            .draw(|frame| app.draw(frame.area(), frame.buffer_mut()))?;
        crossterm::queue!(self.terminal.backend_mut(), EndSynchronizedUpdate)?;
        self.terminal.backend_mut().flush()?;
        let bytes = self.counter.get() - before;
        app.stats.record_frame(Instant::now(), bytes);
        app.last_frame_active = active;
        Ok(bytes)
    }

    /// Bytes written since the screen was made.
    pub fn bytes_written(&self) -> u64 {
        self.counter.get()
    }

    pub fn terminal_mut(&mut self) -> &mut Terminal<CrosstermBackend<CountingWriter<W>>> {
        &mut self.terminal
    }
}

/// One turn of the loop after input: run the due physics, then draw if anything changed.
/// Returns the bytes written (0 when nothing was drawn: a scene at rest costs nothing).
pub fn tick<W: Write>(app: &mut App, screen: &mut Screen<W>, elapsed: Duration) -> io::Result<u64> {
    app.advance(elapsed);
    if app.needs_redraw() || app.last_frame_active {
        // (After the world comes to rest, one last frame replaces the rates with "idle".)
        screen.present(app)
    } else {
        app.stats.record_idle(Instant::now());
        Ok(0)
    }
}

/// Runs the sandbox on the real terminal until the user quits or a signal arrives. The terminal is
/// restored on every way out: return, error (guard `Drop`) and panic (the guard's hook).
pub fn run(scene: Scene, config: AppConfig, fps: u32) -> anyhow::Result<()> {
    let stop = crate::term::install_signal_flags()?;
    let mut guard = TerminalGuard::enter(config.hover)?;
    let mut screen = Screen::new(io::stdout())?;
    screen.terminal_mut().clear()?;
    let mut app = App::new(scene, config);
    let frame_time = Duration::from_secs_f64(1.0 / fps.clamp(1, 240) as f64);
    let mut last_tick = Instant::now();
    let mut last_frame = Instant::now() - frame_time;

    while !app.should_quit() && !stop.load(Ordering::Relaxed) {
        let wait = if app.needs_redraw() {
            frame_time.saturating_sub(last_frame.elapsed())
        } else {
            IDLE_WAIT
        };
        if event::poll(wait)? {
            // Drain everything that is queued so a click acts on the very next physics step.
            loop {
                app.handle_event(&event::read()?);
                if !event::poll(Duration::ZERO)? {
                    break;
                }
            }
        }
        if app.needs_redraw() && last_frame.elapsed() < frame_time {
            continue;
        }
        let now = Instant::now();
        let drew = tick(&mut app, &mut screen, now - last_tick)? > 0;
        last_tick = now;
        if drew {
            last_frame = now;
        }
    }
    drop(screen);
    guard.restore()?;
    Ok(())
}
