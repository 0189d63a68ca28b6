//! Pixel classes drawn with characters, row by row, for the parse stage's tests.

use crate::model::PixelClass;

/// The classes of `rows` (all the same length), row-major, with the width and height:
/// `#` block, `y` line, `r` road, `s` strip, anything else other.
pub fn pixel_classes(rows: &[&str]) -> (u32, u32, Vec<PixelClass>) {
    assert!(rows.iter().all(|r| r.len() == rows[0].len()), "ragged rows");
    let classes = rows
        .iter()
        .flat_map(|row| {
            row.chars().map(|c| match c {
                '#' => PixelClass::Block,
                'y' => PixelClass::Line,
                'r' => PixelClass::Road,
                's' => PixelClass::Strip,
                _ => PixelClass::Other,
            })
        })
        .collect();
    (rows[0].len() as u32, rows.len() as u32, classes)
}
