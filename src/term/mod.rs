//! The terminal layer: turns a pixel buffer into terminal cells, and owns the terminal.
//!
//! Input is always a plain row-major `&[Rgb]` slice (y down, pixel (x, y) at `y * width + x`) with
//! its width and height, so this layer knows nothing of physics, scenes or the rasterizer.
//! A cell shows two vertically stacked pixels, or in the finer [`cells`] modes 2×2, 2×3 or 2×4
//! pixels in two colours.
//!
//! - [`color_depth`]: [`ColorDepth`] (truecolor / 256 / 16) and its detection from
//!   `COLORTERM`/`TERM` ([`detect`], [`detect_from_env`]), uncertain over ssh.
//! - [`palette`]: the 256- and 16-colour palettes in OKLab and linear light, and the perceptual cost
//!   of showing one colour as another (losing chroma charged extra).
//! - [`quantize`](mod@quantize): the perceptually nearest colour a depth can show.
//! - [`fidelity`]: how faithfully cells show a picture, against its truecolor frame (2×2 blends,
//!   OKLab).
//! - [`dither`]: [`Dither`]: ordered 2×2 pattern dithering that stays still, memoised per colour.
//! - [`half_block`]: [`HalfBlocks`], the pure widget drawing two pixels per cell with `▀`.
//! - [`cells`]: [`CellMode`] (half, quadrant, sextant, octant) and [`CellView`], the widget that
//!   draws a pixel buffer in any of them.
//! - [`mosaic`]: [`Mosaic`], the quadrant, sextant and octant widget; [`fit`](mod@fit) chooses each
//!   cell's split of its pixels and two colours (OKLab), [`glyphs`] the character for the split.
//! - [`test_card`](mod@test_card): `nudge cells`, every mode's glyphs and a ball drawn in it.
//! - [`plain`]: `--plain` output, one density character per cell ([`plain_lines`]).
//! - [`ansi`]: a ratatui `Buffer` printed as SGR-coloured text for `nudge snapshot`
//!   ([`buffer_to_ansi`]).
//! - [`probe`]: asks the terminal whether it does truecolor (DECRQSS, XTGETTCAP, then DA1), with a
//!   100 ms deadline, for when the environment cannot say.
//! - [`guard`]: [`TerminalGuard`]: raw mode, alternate screen, hidden cursor and press/drag mouse
//!   reporting, restored in `Drop` and in a chained panic hook, suspended and resumed for job control.
//! - [`signals`]: [`Signals`] turns fatal signals, SIGTSTP and SIGCONT into requests the event loop
//!   answers (restore and exit with 128 + the signal, stop, set up again), and
//!   [`exit_after_hangup`] ends a process whose terminal hung up even if the loop is stuck.
//! - [`unusable_term`]: `TERM=dumb` is refused by the sandbox, with what to run instead.
//! - [`counting`]: [`CountingWriter`], counting bytes sent to the terminal ([`ByteCounter`]).
//! - [`cell_aspect`](mod@cell_aspect): a cell's height/width from a setting or the reported pixel
//!   size ([`cell_aspect()`]).
//!
//! Typical wiring in the app:
//!
//! ```no_run
//! use nudge::term::{CountingWriter, Signals, TerminalGuard};
//! use ratatui::{Terminal, backend::CrosstermBackend};
//!
//! # fn main() -> std::io::Result<()> {
//! let signals = Signals::install()?;
//! let guard = TerminalGuard::enter(false)?;
//! let writer = CountingWriter::new(std::io::stdout());
//! let bytes = writer.counter();
//! let mut terminal = Terminal::new(CrosstermBackend::new(writer))?;
//! // loop { if let Some(request) = signals.take() { .. } draw(HalfBlocks::new(..)); ... }
//! drop(terminal);
//! drop(guard); // restores the terminal (also on panic)
//! # Ok(())
//! # }
//! ```

pub mod ansi;
pub mod cell_aspect;
pub mod cells;
pub mod color_depth;
pub mod counting;
pub mod dither;
pub mod fidelity;
pub mod fit;
pub mod glyphs;
pub mod guard;
pub mod half_block;
pub mod mosaic;
pub mod palette;
pub mod plain;
pub mod probe;
pub mod quantize;
pub mod signals;
pub mod test_card;

pub use ansi::buffer_to_ansi;
pub use cell_aspect::{DEFAULT_CELL_ASPECT, cell_aspect};
pub use cells::{CellMode, CellView};
pub use color_depth::{
    ColorDepth, Detected, check_term_env, detect, detect_from_env, guessed_hint, unusable_term,
};
pub use counting::{ByteCounter, CountingWriter};
pub use dither::Dither;
pub use guard::{TerminalGuard, restore_terminal};
pub use half_block::HalfBlocks;
pub use mosaic::Mosaic;
pub use plain::plain_lines;
pub use quantize::{ansi16_index, ansi256_index, ansi256_rgb, quantize};
pub use signals::{EndedBySignal, SignalRequest, Signals, exit_after_hangup};
