//! LayoutError: why a user's layout image could not be read.

use thiserror::Error;

/// Why [`super::decode`] refused a layout image.
#[derive(Debug, Error)]
pub enum LayoutError {
    /// The bytes are neither PNG nor JPEG.
    #[error("the layout image is not a PNG or JPEG file")]
    UnknownFormat,
    /// The header announces an image too large to decode.
    #[error(
        "the layout image is {width}×{height} px; at most {max_side} px a side and \
         {max_pixels} pixels are accepted"
    )]
    TooLarge {
        width: u32,
        height: u32,
        max_side: u32,
        max_pixels: u64,
    },
    /// The image has no pixels.
    #[error("the layout image is empty (0 px wide or high)")]
    Empty,
    /// The file ends before its end marker (a download or copy cut short).
    #[error("the layout image is {0}")]
    Truncated(String),
    /// The decoder rejected the data (truncated or corrupt file).
    #[error("the layout image could not be decoded: {0}")]
    Decode(#[source] image::ImageError),
}
