//! Image files in and out, for every stage: whether a PNG or JPEG is whole, a user's layout
//! image decoded within size limits, PNG encoding with fixed settings, float32 `.npy` files.
//!
//! Shared because more than one stage needs each: the layout stage and the spec's checks
//! decode layout images the same way, the renderer and the sensor develop colour alike, the facades stage refuses cut-off photos with the
//! same end check, and textures, builtin facade labels and rendered frames are all PNGs
//! whose bytes must not depend on who wrote them; the renderer and the WebDataset shards
//! write float32 depth as the same `.npy`.

mod decode;
mod image_end;
mod layout_error;
mod npy;
mod png;
mod rgb8;

pub use decode::{MAX_PIXELS, MAX_SIDE, decode};
pub use image_end::check_complete;
pub use layout_error::LayoutError;
pub use npy::npy_f32;
pub use png::{PngEffort, encode_png};
pub use rgb8::rgb8_by_channel;
