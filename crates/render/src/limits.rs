//! The size limits of a picture, shared by the checks and their error messages.

/// The smallest side of a picture, in pixels.
pub const MIN_SIDE: u32 = 16;
/// The largest side of a picture (or of one panel), in pixels.
pub const MAX_SIDE: u32 = 8192;
/// The most pixels a whole picture (a strip of panels) may have: 64 Mi, so one picture stays
/// under a few hundred MiB while it is drawn.
pub const MAX_PIXELS: u64 = 1 << 26;
