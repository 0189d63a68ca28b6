//! PixelClass: which layout element a layout-image pixel was drawn as.
//!
//! One enum for every reader of a layout image: the spec's palette checks, the parse stage's
//! class map and the lamps stage's road sides all name a pixel's class with it.

/// The layout element a pixel shows, by its palette colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum PixelClass {
    /// No palette colour within the tolerance.
    Other,
    Road,
    Line,
    Block,
    Strip,
}
