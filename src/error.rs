//! The errors refrast returns: every bad input is named, nothing panics.

use std::fmt;

/// Why an implementation cannot be built on this machine (no driver, no such adapter): a
/// runner reports it and skips the implementation instead of judging it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unavailable(pub String);

impl fmt::Display for Unavailable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Unavailable {}

/// A configuration value out of its documented range.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConfigError {
    /// Subpixel bits outside `SubpixelBits::MIN..=SubpixelBits::MAX`.
    SubpixelBits(u8),
    /// A viewport side of zero or above [`MAX_VIEWPORT`](crate::MAX_VIEWPORT).
    Viewport {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
    },
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::SubpixelBits(bits) => write!(
                f,
                "{bits} subpixel bits is not supported: use {}..={}",
                crate::SubpixelBits::MIN,
                crate::SubpixelBits::MAX
            ),
            Self::Viewport { width, height } => write!(
                f,
                "viewport {width}x{height} is not supported: each side must be 1..={}",
                crate::MAX_VIEWPORT
            ),
        }
    }
}

impl std::error::Error for ConfigError {}

/// Why a draw was refused as a whole; triangles with bad numbers are discarded, not errors.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DrawError {
    /// A triangle names a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle (primitive index) holding the bad index.
        triangle: usize,
        /// The bad vertex index.
        index: u32,
        /// How many vertices the draw has.
        vertices: usize,
    },
    /// The implementation cannot do what the draw asks (named in the message).
    Unsupported(String),
    /// The implementation failed for a reason of its own (a device lost, a driver error).
    Backend(String),
    /// The implementation broke the contract itself: a child process that crashed, hung or
    /// answered garbage. A failure under every rule, even one that expects an error.
    Misbehaved(String),
}

impl fmt::Display for DrawError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::IndexOutOfRange {
                triangle,
                index,
                vertices,
            } => write!(
                f,
                "triangle {triangle} uses vertex {index}, but the draw has only {vertices} vertices"
            ),
            Self::Unsupported(what) => write!(f, "unsupported by this rasterizer: {what}"),
            Self::Backend(why) => write!(f, "rasterizer backend failed: {why}"),
            Self::Misbehaved(what) => write!(f, "the rasterizer misbehaved: {what}"),
        }
    }
}

impl std::error::Error for DrawError {}
