//! The terminal layer: turns a pixel buffer into terminal cells, and owns the terminal.
//!
//! Input is always a plain row-major `&[Rgb]` slice (y down) with its width and height, so this layer
//! knows nothing of physics, scenes or the rasterizer.
//!
//! - [`color_depth`]: [`ColorDepth`] and its detection from `COLORTERM`/`TERM`.
//! - [`quantize`](mod@quantize): nearest palette colour for a depth (O(1) for 256 colours).
//! - [`half_block`]: [`HalfBlocks`], the pure widget drawing two pixels per cell with `▀`.
//! - [`ansi`]: a ratatui `Buffer` printed as SGR-coloured text for `nudge snapshot` ([`buffer_to_ansi`]).
//! - [`plain`]: `--plain` output, one density character per cell ([`plain_lines`]).

pub mod ansi;
pub mod color_depth;
pub mod half_block;
pub mod plain;
pub mod quantize;

pub use ansi::buffer_to_ansi;
pub use color_depth::{ColorDepth, Detected, ParseColorDepthError, detect, detect_from_env};
pub use half_block::HalfBlocks;
pub use plain::plain_lines;
pub use quantize::{ansi16_index, ansi256_index, ansi256_rgb, quantize};
