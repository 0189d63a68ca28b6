//! ClassMap: layout image + palette → one palette class per pixel.

use image::RgbImage;
use rayon::prelude::*;

use crate::model::PixelClass;
use crate::spec::{Color, Palette};

/// Smallest share of line colour in a road/line blend that still counts as line: a 1-px
/// line under a 3×3 box blur keeps 1/3 of its colour in each of three rows.
const LINE_BLEND_MIN: i64 = 4; // the share is at least 1 / LINE_BLEND_MIN

/// The class of every pixel of a layout image, row-major.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ClassMap {
    width: u32,
    height: u32,
    classes: Vec<PixelClass>,
}

impl ClassMap {
    /// Classifies every pixel of `image` (see [`Classifier`]); rows run in parallel, and the
    /// map is the same whatever the thread count.
    pub fn classify(image: &RgbImage, palette: &Palette) -> ClassMap {
        let (width, height) = image.dimensions();
        let (w, h) = (width as usize, height as usize);
        let mut classes = vec![PixelClass::Other; w * h];
        if w > 0 {
            let classifier = Classifier::new(palette);
            let raw = &image.as_raw()[..w * h * 3];
            classes
                .par_chunks_mut(w)
                .zip(raw.par_chunks(w * 3))
                .for_each(|(out, row)| classifier.classify_row(row, out));
        }
        ClassMap {
            width,
            height,
            classes,
        }
    }

    /// A map drawn with characters, row by row (see
    /// [`crate::test_support::pixel_classes`]).
    #[cfg(test)]
    pub fn drawn(rows: &[&str]) -> ClassMap {
        let (width, height, classes) = crate::test_support::pixel_classes(rows);
        ClassMap {
            width,
            height,
            classes,
        }
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// The classes of row `y`.
    pub fn row(&self, y: u32) -> &[PixelClass] {
        let w = self.width as usize;
        &self.classes[y as usize * w..][..w]
    }

    #[cfg(test)]
    pub fn get(&self, x: u32, y: u32) -> PixelClass {
        self.classes[y as usize * self.width as usize + x as usize]
    }
}

/// The per-pixel rule. A pixel takes the nearest palette colour (Euclidean RGB, ties in the
/// order road, line, block, strip) if it lies within `palette.tolerance`; otherwise it is
/// [`PixelClass::Other`]. One exception keeps thin lines alive: anti-aliasing, blurring or JPEG
/// chroma subsampling spread a 1-px line over its neighbours at reduced strength, which the
/// nearest-colour rule would call road. So a pixel that is road or other also counts as
/// [`PixelClass::Line`] when it is a blend of road and line colour with at least a quarter of line
/// colour, within `tolerance` of that blend.
struct Classifier {
    palette: Palette,
    road: [i32; 3],
    /// line − road, and its squared length.
    towards_line: [i32; 3],
    towards_line_sq: i64,
    tolerance_sq: i64,
}

impl Classifier {
    fn new(palette: &Palette) -> Classifier {
        let rgb = |c: Color| c.0.map(i32::from);
        let road = rgb(palette.road);
        let line = rgb(palette.line);
        let towards_line = [line[0] - road[0], line[1] - road[1], line[2] - road[2]];
        Classifier {
            palette: palette.clone(),
            road,
            towards_line,
            towards_line_sq: dot(towards_line, towards_line),
            tolerance_sq: i64::from(palette.tolerance).pow(2),
        }
    }

    fn classify_row(&self, row: &[u8], out: &mut [PixelClass]) {
        // Layouts are mostly flat colour: reuse the previous answer for a repeated pixel.
        let mut last: Option<([u8; 3], PixelClass)> = None;
        for (slot, px) in out.iter_mut().zip(row.chunks_exact(3)) {
            let px = [px[0], px[1], px[2]];
            *slot = match last {
                Some((seen, class)) if seen == px => class,
                _ => {
                    let class = self.class(px);
                    last = Some((px, class));
                    class
                }
            };
        }
    }

    fn class(&self, px: [u8; 3]) -> PixelClass {
        let p = px.map(i32::from);
        let (nearest, dist) = self.palette.nearest(px);
        let near = i64::from(dist) <= self.tolerance_sq;
        match nearest {
            PixelClass::Line if near => PixelClass::Line,
            PixelClass::Block | PixelClass::Strip if near => nearest,
            _ if self.is_line_blend(p) => PixelClass::Line,
            PixelClass::Road if near => PixelClass::Road,
            _ => PixelClass::Other,
        }
    }

    /// Whether `p` is within tolerance of `road + t·(line − road)` for some `t ≥ 1/4`.
    fn is_line_blend(&self, p: [i32; 3]) -> bool {
        let span = self.towards_line_sq;
        if span == 0 {
            return false;
        }
        let q = [
            p[0] - self.road[0],
            p[1] - self.road[1],
            p[2] - self.road[2],
        ];
        let along = dot(q, self.towards_line); // t · span
        if along * LINE_BLEND_MIN < span {
            return false;
        }
        if along >= span {
            // Beyond the line colour: the distance to the line colour itself.
            let d = [
                q[0] - self.towards_line[0],
                q[1] - self.towards_line[1],
                q[2] - self.towards_line[2],
            ];
            return dot(d, d) <= self.tolerance_sq;
        }
        // Squared distance to the blend, times span: |q|²·span − along².
        dot(q, q) * span - along * along <= self.tolerance_sq * span
    }
}

fn dot(a: [i32; 3], b: [i32; 3]) -> i64 {
    (0..3).map(|i| i64::from(a[i]) * i64::from(b[i])).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgb;

    fn class_of(rgb: [u8; 3]) -> PixelClass {
        let image = RgbImage::from_pixel(1, 1, Rgb(rgb));
        ClassMap::classify(&image, &Palette::default()).get(0, 0)
    }

    #[test]
    fn pixels_take_the_nearest_palette_colour_within_tolerance() {
        let mix = |a: [u8; 3], b: [u8; 3], wa: u32, wb: u32| {
            [0, 1, 2].map(|i| {
                ((u32::from(a[i]) * wa + u32::from(b[i]) * wb + (wa + wb) / 2) / (wa + wb)) as u8
            })
        };
        let p = Palette::default();
        let (road, line, block, strip) = (p.road.0, p.line.0, p.block.0, p.strip.0);
        let cases = [
            ("road", road, PixelClass::Road),
            ("line", line, PixelClass::Line),
            ("block", block, PixelClass::Block),
            ("strip", strip, PixelClass::Strip),
            ("noisy road", [135, 121, 130], PixelClass::Road),
            ("noisy block", [50, 90, 200], PixelClass::Block),
            ("white", [255, 255, 255], PixelClass::Other),
            ("black", [0, 0, 0], PixelClass::Other),
            ("red", [255, 0, 0], PixelClass::Other),
            (
                "blue/strip half",
                mix(block, strip, 1, 1),
                PixelClass::Other,
            ),
            (
                "two-thirds block",
                mix(block, strip, 2, 1),
                PixelClass::Block,
            ),
            (
                "two-thirds road by strip",
                mix(road, strip, 2, 1),
                PixelClass::Road,
            ),
            ("line blurred 1/3", mix(line, road, 1, 2), PixelClass::Line),
            ("line blurred 1/5", mix(line, road, 1, 4), PixelClass::Road),
            ("half line", mix(line, road, 1, 1), PixelClass::Line),
            ("line over strip", mix(line, strip, 1, 2), PixelClass::Strip),
        ];
        for (name, rgb, expected) in cases {
            assert_eq!(class_of(rgb), expected, "{name} {rgb:?}");
        }
    }

    #[test]
    fn a_palette_without_line_contrast_does_not_divide_by_zero() {
        let palette = Palette {
            line: Palette::default().road,
            ..Palette::default()
        };
        let image = RgbImage::from_pixel(2, 1, Rgb([128, 128, 128]));
        let map = ClassMap::classify(&image, &palette);
        assert_eq!(map.row(0), &[PixelClass::Road, PixelClass::Road]);
    }

    #[test]
    fn classification_does_not_depend_on_thread_count() {
        let image = RgbImage::from_fn(97, 61, |x, y| {
            Rgb([(x * 37 + y * 11) as u8, (x * y) as u8, (x + 3 * y) as u8])
        });
        let palette = Palette::default();
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let four = rayon::ThreadPoolBuilder::new()
            .num_threads(4)
            .build()
            .unwrap();
        let a = one.install(|| ClassMap::classify(&image, &palette));
        let b = four.install(|| ClassMap::classify(&image, &palette));
        assert_eq!(a, b);
    }
}
