//! Building widths in metres → building sides in layout pixels, as placement takes them.

/// Building widths in layout pixels (at least one pixel each).
pub fn widths_px(widths_m: &[f64], metres_per_pixel: f64) -> Vec<u32> {
    widths_m
        .iter()
        .map(|w| (w / metres_per_pixel).round().max(1.0) as u32)
        .collect()
}
