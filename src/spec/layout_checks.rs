//! Layout checks: a schema-valid [`LayoutSpec`] + the world's image headers and pixels →
//! the problems the schema cannot see (one layout source, roads that fit, a whole image of
//! sane size drawn in the palette, a mirrored city that is not absurdly large), and the
//! layout's extent for the cost checks.

use std::path::Path;

use image::RgbImage;

use super::cost_checks::LayoutExtent;
use super::findings::Findings;
use super::spec::{GenerateSpec, LayoutSpec, Palette};
use super::{SpecWorld, resolve};
use crate::model::PixelClass;

/// Largest side of a layout image, drawn, generated or mirrored, in pixels.
pub const MAX_LAYOUT_SIDE: u64 = 16384;
/// Largest layout image area in pixels (64 Mpx).
pub const MAX_LAYOUT_PIXELS: u64 = 64 * 1024 * 1024;

/// Checks `layout`; `spec_path` is the spec's path as given, against which the image
/// resolves. Returns the mirrored layout's extent when the layout is sound.
pub(crate) fn check_layout(
    layout: &LayoutSpec,
    spec_path: &Path,
    world: &dyn SpecWorld,
    findings: &mut Findings<'_, '_>,
) -> Option<LayoutExtent> {
    let mut base = None;
    if layout.osm.is_some() {
        // A map: `map_checks` checks it; no other source may be given beside it.
        for other in ["layout.generate", "layout.image"] {
            if findings.written(other) {
                let line = findings.line_of("layout.osm");
                findings.error(
                    other,
                    format!(
                        "expected one layout source, found `{other}` beside `[layout.osm]` \
                         (on line {line})"
                    ),
                );
            }
        }
        return None;
    }
    match (&layout.generate, &layout.image) {
        (None, None) => findings.error(
            "layout",
            "expected a layout source, `[layout.generate]`, `layout.image = \"….png\"` or \
             `[layout.osm]`, found none",
        ),
        (Some(_), Some(_)) => {
            let line = findings.line_of("layout.generate");
            findings.error(
                "layout.image",
                format!(
                    "expected either `layout.generate` or `layout.image`, found both \
                     (`layout.generate` is on line {line})"
                ),
            );
        }
        (Some(generate), None) => {
            if check_generate(generate, findings) {
                base = Some(generated_extent(generate));
            }
        }
        (None, Some(_)) => {}
    }
    if let Some(image) = &layout.image {
        let extent = check_image(image, &layout.palette, spec_path, world, findings);
        if layout.generate.is_none() {
            base = extent;
        }
    }
    let base = base?;
    check_mirror(&layout.mirror, base.width, base.height, findings).then(|| {
        let doublings = layout
            .mirror
            .iter()
            .map(|&op| if op == 3 { 2 } else { 1 })
            .sum::<u32>();
        let (mut w, mut h) = (base.width, base.height);
        for op in &layout.mirror {
            if *op != 1 {
                w *= 2;
            }
            if *op != 2 {
                h *= 2;
            }
        }
        LayoutExtent {
            width: w,
            height: h,
            block_px: base.block_px << doublings,
            line_px: base.line_px << doublings,
        }
    })
}

/// A generated layout's extent: blocks fill what the roads and strips leave.
fn generated_extent(g: &GenerateSpec) -> LayoutExtent {
    let (w, h) = (u64::from(g.width), u64::from(g.height));
    let (nh, nv) = (u64::from(g.horizontal_roads), u64::from(g.vertical_roads));
    let (road, strip) = (u64::from(g.road_width), u64::from(g.strip_width));
    let blocks_w = w.saturating_sub(nv * road + 2 * strip * (nv + 1));
    let blocks_h = h.saturating_sub(nh * road + 2 * strip * (nh + 1));
    LayoutExtent {
        width: w,
        height: h,
        block_px: blocks_w * blocks_h,
        line_px: nh * w + nv * h,
    }
}

/// Checks the generator's roads fit its image; true when it is sound.
fn check_generate(g: &GenerateSpec, findings: &mut Findings<'_, '_>) -> bool {
    let (w, h) = (u64::from(g.width), u64::from(g.height));
    let road = u64::from(g.road_width);
    let smaller = w.min(h);
    if road >= smaller {
        findings.error(
            "layout.generate.road_width",
            format!(
                "a road wider than the layout: expected a road_width below {smaller} px \
                 (the layout is {w}×{h} px), found {}",
                findings.shown("layout.generate.road_width", road)
            ),
        );
        return false;
    }
    let cell = u64::from(g.min_block) + 2 * u64::from(g.strip_width);
    if cell > smaller {
        findings.error(
            "layout.generate.min_block",
            format!(
                "blocks do not fit: expected min_block + 2 × strip_width at most {smaller} px \
                 (the layout is {w}×{h} px), found {} + 2 × {} = {cell}",
                g.min_block, g.strip_width
            ),
        );
        return false;
    }
    let mut sound = true;
    let directions = [
        ("horizontal_roads", g.horizontal_roads, h, "high"),
        ("vertical_roads", g.vertical_roads, w, "wide"),
    ];
    for (name, count, size, adjective) in directions {
        let n = u64::from(count);
        if n * road + (n + 1) * cell > size {
            let fit = (size - cell) / (road + cell);
            let key = format!("layout.generate.{name}");
            let what = name.replace('_', " ");
            let what = if fit == 1 {
                what.trim_end_matches('s')
            } else {
                &what
            };
            findings.error(
                &key,
                format!(
                    "too many roads: expected at most {fit} {what} in a layout {size} px \
                     {adjective} (each road takes {road} px, each block at least {cell} px with \
                     its strips), found {}",
                    findings.shown(&key, n)
                ),
            );
            sound = false;
        }
    }
    if g.horizontal_roads == 0 && g.vertical_roads == 0 {
        let key = if findings.written("layout.generate.vertical_roads") {
            "layout.generate.vertical_roads"
        } else {
            "layout.generate.horizontal_roads"
        };
        findings.error(
            key,
            "a layout without roads: expected at least one road (horizontal_roads or \
             vertical_roads), found none; lamps stand along roads and cameras drive on them",
        );
    }
    sound
}

/// Checks the image exists, is a whole image of sane size and is drawn in the palette; its
/// extent when sound.
fn check_image(
    image: &str,
    palette: &Palette,
    spec_path: &Path,
    world: &dyn SpecWorld,
    findings: &mut Findings<'_, '_>,
) -> Option<LayoutExtent> {
    let resolved = resolve(spec_path, image);
    let (w, h) = check_image_size(&resolved, world, findings)?;
    // Worlds that do not decode pixels (tests) get an upper bound.
    let mut extent = LayoutExtent {
        width: w,
        height: h,
        block_px: w * h,
        line_px: w + h,
    };
    match world.layout_pixels(&resolved) {
        None => {}
        Some(Err(problem)) => {
            findings.error(
                "layout.image",
                format!(
                    "expected a whole PNG or JPEG layout image at {}, found {problem}",
                    resolved.display()
                ),
            );
            return None;
        }
        Some(Ok(pixels)) => {
            let [_, line, block, _] = check_pixels(&pixels, palette, &resolved, world, findings)?;
            extent.block_px = block;
            extent.line_px = line;
        }
    }
    Some(extent)
}

/// The image's width and height when it is an image of at most [`MAX_LAYOUT_SIDE`] a side
/// and [`MAX_LAYOUT_PIXELS`] in all.
fn check_image_size(
    resolved: &Path,
    world: &dyn SpecWorld,
    findings: &mut Findings<'_, '_>,
) -> Option<(u64, u64)> {
    let (w, h) = match world.image_dimensions(resolved) {
        Err(problem) => {
            findings.error(
                "layout.image",
                format!(
                    "expected a PNG or JPEG layout image at {}, found {problem}",
                    resolved.display()
                ),
            );
            return None;
        }
        Ok((w, h)) => (u64::from(w), u64::from(h)),
    };
    if too_large(w, h) {
        findings.error(
            "layout.image",
            format!(
                "the image is too large: expected at most {MAX_LAYOUT_SIDE} px a side \
                 and {} Mpx, found {w}×{h} px in {}",
                MAX_LAYOUT_PIXELS >> 20,
                resolved.display()
            ),
        );
        return None;
    }
    Some((w, h))
}

/// The pixel counts per palette class (road, line, block, strip) when the image is drawn
/// in the palette and roads and blocks can be read off it.
fn check_pixels(
    pixels: &RgbImage,
    palette: &Palette,
    resolved: &Path,
    world: &dyn SpecWorld,
    findings: &mut Findings<'_, '_>,
) -> Option<[u64; 4]> {
    let counts = palette_counts(pixels, palette);
    let [road, line, block, _] = counts;
    if road + line == 0 || block == 0 {
        let missing = match (road + line == 0, block == 0) {
            (true, true) => "neither road nor block colours",
            (true, false) => "no road colours",
            _ => "no block colours",
        };
        findings.error(
            "layout.image",
            format!(
                "expected a layout drawn with the palette (road {}, line {}, block {}, \
                 strip {}, within {} of each), found {missing} in {}; its most common \
                 colours are {}; draw with the palette or set `[layout.palette]` to \
                 the image's colours",
                palette.road,
                palette.line,
                palette.block,
                palette.strip,
                palette.tolerance,
                resolved.display(),
                most_common(pixels, 3)
            ),
        );
        return None;
    }
    if let Some((roads, blocks)) = world.parsed_layout(pixels, palette)
        && (roads == 0 || blocks == 0)
    {
        findings.error(
            "layout.image",
            format!(
                "expected a layout from which roads and blocks can be read, found \
                 {roads} road{} and {blocks} block{} in {} (palette road {}, line {}, \
                 block {}, strip {}, within {}: {road} road, {line} line, {block} \
                 block and {} strip pixels); a road needs a centre line in the line \
                 colour, a block an area in the block colour: is this a layout \
                 drawing?",
                plural(roads),
                plural(blocks),
                resolved.display(),
                palette.road,
                palette.line,
                palette.block,
                palette.strip,
                palette.tolerance,
                counts[3],
            ),
        );
        return None;
    }
    Some(counts)
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// Pixels of each palette colour: road, line, block, strip.
fn palette_counts(image: &RgbImage, palette: &Palette) -> [u64; 4] {
    let mut counts = [0u64; 4];
    for pixel in image.pixels() {
        let slot = match palette.classify(pixel.0) {
            PixelClass::Road => 0,
            PixelClass::Line => 1,
            PixelClass::Block => 2,
            PixelClass::Strip => 3,
            PixelClass::Other => continue,
        };
        counts[slot] += 1;
    }
    counts
}

/// The `n` most common exact colours with their shares, e.g. `#ffffff (71 %), …`.
fn most_common(image: &RgbImage, n: usize) -> String {
    let mut colours: Vec<u32> = image
        .pixels()
        .map(|p| u32::from_be_bytes([0, p.0[0], p.0[1], p.0[2]]))
        .collect();
    colours.sort_unstable();
    let total = colours.len().max(1) as f64;
    let mut runs: Vec<(usize, u32)> = colours
        .chunk_by(|a, b| a == b)
        .map(|run| (run.len(), run[0]))
        .collect();
    // Most pixels first; ties by colour, so the message is deterministic.
    runs.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
    runs.iter()
        .take(n)
        .map(|&(count, rgb)| format!("#{rgb:06x} ({:.0} %)", 100.0 * count as f64 / total))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Checks the mirrored city stays within the size limits; true when it does.
fn check_mirror(ops: &[u8], width: u64, height: u64, findings: &mut Findings<'_, '_>) -> bool {
    let (mut w, mut h) = (width, height);
    for op in ops {
        match op {
            1 => h *= 2,
            2 => w *= 2,
            3 => (w, h) = (w * 2, h * 2),
            _ => {}
        }
    }
    if too_large(w, h) {
        findings.error(
            "layout.mirror",
            format!(
                "the mirrored layout is too large: expected at most {MAX_LAYOUT_SIDE} px a side \
                 and {} Mpx, found {w}×{h} px ({width}×{height} mirrored by {ops:?}); \
                 drop some mirror operations",
                MAX_LAYOUT_PIXELS >> 20
            ),
        );
        return false;
    }
    true
}

fn too_large(w: u64, h: u64) -> bool {
    w > MAX_LAYOUT_SIDE || h > MAX_LAYOUT_SIDE || w * h > MAX_LAYOUT_PIXELS
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use image::RgbImage;

    use super::super::{Palette, SpecWorld};
    use crate::test_support::FakeWorld;

    /// A world whose one layout image has pixels of every palette colour, and which parses
    /// it to the given roads and blocks.
    struct ParsingWorld(usize, usize);

    impl SpecWorld for ParsingWorld {
        fn image_dimensions(&self, _: &Path) -> Result<(u32, u32), String> {
            Ok((4, 1))
        }
        fn folder(&self, _: &Path) -> Result<(), String> {
            Ok(())
        }
        fn spec_text(&self, _: &Path) -> Result<String, String> {
            Err("no such file".to_string())
        }
        fn file(&self, _: &Path) -> Result<(), String> {
            Ok(())
        }
        fn layout_pixels(&self, _: &Path) -> Option<Result<RgbImage, String>> {
            let p = Palette::default();
            let pixels = [p.road, p.line, p.block, p.strip]
                .into_iter()
                .flat_map(|c| c.0);
            RgbImage::from_raw(4, 1, pixels.collect()).map(Ok)
        }
        fn parsed_layout(&self, _: &RgbImage, _: &Palette) -> Option<(usize, usize)> {
            Some((self.0, self.1))
        }
    }

    #[test]
    fn an_image_the_parse_stage_reads_nothing_off_is_refused() {
        let text = "version = 1\nname = \"c\"\n[layout]\nimage = \"a.png\"\n";
        let source = super::super::SpecSource {
            path: "c.toml".into(),
            text: text.to_string(),
        };
        let cases = [
            ((1, 1), None),
            ((0, 1), Some("found 0 roads and 1 block in a.png")),
            ((1, 0), Some("found 1 road and 0 blocks in a.png")),
        ];
        for ((roads, blocks), want) in cases {
            let got = super::super::load(&source, &ParsingWorld(roads, blocks));
            match (got, want) {
                (Ok(_), None) => {}
                (Err(e), Some(want)) => {
                    let e = e.to_string();
                    assert!(e.contains(want), "{e}");
                    assert!(
                        e.contains("1 road, 1 line, 1 block and 1 strip pixels"),
                        "{e}"
                    );
                }
                (got, want) => panic!("{roads} roads, {blocks} blocks: {got:?}, want {want:?}"),
            }
        }
    }

    /// Images `a.png` (640×480) and `big.png` (9000×9000) beside `specs/city.toml`.
    fn problems(body: &str) -> Vec<String> {
        let world =
            FakeWorld::with_images(&[("specs/a.png", (640, 480)), ("specs/big.png", (9000, 9000))]);
        let text = format!("version = 1\nname = \"c\"\n{body}");
        world
            .load("specs/city.toml", text)
            .err()
            .unwrap_or_default()
    }

    #[test]
    fn layout_problems_name_the_responsible_key() {
        let cases: &[(&str, &[&str])] = &[
            ("[layout.generate]\n", &[]),
            ("[layout]\nimage = \"a.png\"\nmirror = [3, 3, 3]\n", &[]),
            ("[layout]\n", &["layout: expected a layout source"]),
            (
                "[layout]\nimage = \"a.png\"\n[layout.generate]\n",
                &[
                    "layout.image: expected either `layout.generate` or `layout.image`, found both (`layout.generate` is on line 5)",
                ],
            ),
            (
                "[layout]\nimage = \"b.png\"\n",
                &[
                    "layout.image: expected a PNG or JPEG layout image at specs/b.png, found no such file",
                ],
            ),
            (
                "[layout]\nimage = \"big.png\"\n",
                &[
                    "layout.image: the image is too large: expected at most 16384 px a side and 64 Mpx, found 9000×9000 px in specs/big.png",
                ],
            ),
            (
                "[layout]\nimage = \"a.png\"\nmirror = [3, 3, 3, 3, 3]\n",
                &[
                    "layout.mirror: the mirrored layout is too large: expected at most 16384 px a side and 64 Mpx, found 20480×15360 px (640×480 mirrored by [3, 3, 3, 3, 3])",
                ],
            ),
            (
                "[layout]\nimage = \"a.png\"\nmirror = [2, 2, 2, 2, 2]\n",
                &[
                    "layout.mirror: the mirrored layout is too large: expected at most 16384 px a side and 64 Mpx, found 20480×480 px",
                ],
            ),
            (
                "[layout.generate]\nwidth = 64\nheight = 100\nroad_width = 64\n",
                &[
                    "layout.generate.road_width: a road wider than the layout: expected a road_width below 64 px (the layout is 64×100 px), found 64",
                ],
            ),
            (
                "[layout.generate]\nwidth = 64\nheight = 64\n",
                &[
                    "layout.generate.min_block: blocks do not fit: expected min_block + 2 × strip_width at most 64 px (the layout is 64×64 px), found 64 + 2 × 8 = 80",
                ],
            ),
            (
                "[layout.generate]\nmin_block = 800\n",
                &[
                    "layout.generate.min_block: blocks do not fit: expected min_block + 2 × strip_width at most 768 px (the layout is 768×768 px), found 800 + 2 × 8 = 816",
                ],
            ),
            // 10 × 32 + 11 × 80 = 1200: exactly fits.
            (
                "[layout.generate]\nwidth = 1200\nvertical_roads = 10\n",
                &[],
            ),
            (
                "[layout.generate]\nwidth = 1199\nvertical_roads = 10\n",
                &[
                    "layout.generate.vertical_roads: too many roads: expected at most 9 vertical roads in a layout 1199 px wide",
                ],
            ),
            (
                "[layout.generate]\nwidth = 1000\nvertical_roads = 10\n",
                &[
                    "layout.generate.vertical_roads: too many roads: expected at most 8 vertical roads in a layout 1000 px wide (each road takes 32 px, each block at least 80 px with its strips), found 10",
                ],
            ),
            (
                "[layout.generate]\nhorizontal_roads = 0\nvertical_roads = 0\n",
                &["layout.generate.vertical_roads: a layout without roads"],
            ),
            ("[layout.generate]\nhorizontal_roads = 0\n", &[]),
        ];
        for (body, want) in cases {
            let got = problems(body);
            assert_eq!(got.len(), want.len(), "{body}\n{got:#?}");
            for (g, w) in got.iter().zip(want.iter()) {
                assert!(g.starts_with(w), "{body}\ngot  {g}\nwant {w}…");
            }
        }
    }
}
