//! Cost checks: a spec + the layout's extent → an estimate of what the build will make
//! ([`CostEstimate`]) and the problems of one over the `[limits]` or the instance-id space.
//!
//! Everything is estimated from the spec and the layout alone, before a stage runs, so a
//! spec that would run a machine out of memory (issue 8: 1024² with `widths = [1]` and
//! `gap = 0` took 8.6 GB) is refused in milliseconds with the figures and the knob:
//!
//! | what | estimated from |
//! |---|---|
//! | pixels | the layout's size after mirroring |
//! | buildings | block area ÷ (smallest width + gap)², the most Algorithm 1 can place |
//! | lamps | 2 sides × road length ÷ spacing |
//! | objects | the `[[objects]]` counts |
//! | frame memory | the largest camera's resolution × supersampling² |
//! | frame bytes | Σ frames × resolution (a spacing gives length ÷ spacing frames) |
//!
//! The per-item memory figures come from the peak memory of the builds issue 8 measured,
//! rounded up; they are estimates, and `[limits]` is the knob.

use super::camera_spec::{FrameRule, MAX_FRAMES};
use super::findings::Findings;
use super::spec::{BUILTIN_FACADES, Spec};

/// Largest instance id the ids image holds: 24-bit RGB (`id = R + 256·G + 256²·B`).
pub const MAX_INSTANCE_ID: u64 = (1 << 24) - 1;

/// Memory per layout pixel: the image, its mirror, class maps, the preview and PNG codecs.
const BYTES_PER_PIXEL: u64 = 40;
/// Memory per building: its mesh, materials, plan and export entries (issue 8: about 746k
/// buildings on 1024² with `widths = [1]`, `gap = 0` took 8.6 GB).
const BYTES_PER_BUILDING: u64 = 12 * 1024;
/// Memory per lamp: its mesh, light and plan entries (issue 8: 49k lamps on 4096² took
/// 11.5 GB).
const BYTES_PER_LAMP: u64 = 240 * 1024;
/// Memory per inserted object (a text plate's atlas share dominates).
const BYTES_PER_OBJECT: u64 = 16 * 1024;
/// Memory per frame pixel per sample: colour, depth, ids, footprints, the contact sheet.
const BYTES_PER_FRAME_SAMPLE: u64 = 64;
/// What any build holds: the built-in facades, fonts, code.
const BASE_BYTES: u64 = 160 << 20;
/// Output bytes per frame pixel: RGB, ids and depth PNGs (a generous compressed size).
const OUTPUT_BYTES_PER_FRAME_PIXEL: u64 = 6;
/// Narrowest building of the built-in facade set, metres (a test keeps it true).
pub(crate) const BUILTIN_MIN_WIDTH_M: f64 = 7.0;
/// Narrowest building assumed for a facade folder, whose widths are known only once its
/// photos are processed: an estimate, not a bound.
const FOLDER_MIN_WIDTH_M: f64 = 6.0;

/// The layout as validation knows it, after mirroring, in pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct LayoutExtent {
    pub width: u64,
    pub height: u64,
    /// Building-block pixels (an upper bound when the image was not decoded).
    pub block_px: u64,
    /// Centre-line pixels: about the total road length.
    pub line_px: u64,
}

/// What a spec will build, roughly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CostEstimate {
    pub pixels: u64,
    pub buildings: u64,
    pub lamps: u64,
    pub objects: u64,
    /// Peak memory in bytes.
    pub memory: u64,
    /// Bytes the frames write.
    pub output: u64,
}

impl CostEstimate {
    /// Instance ids the scene needs (every building, lamp and object, and a few per block
    /// and road for the ground, which are counted in pixels' stead).
    pub fn instances(&self) -> u64 {
        self.buildings + self.lamps + self.objects
    }
}

/// The estimate for `spec` on `layout`.
pub(crate) fn estimate(spec: &Spec, layout: LayoutExtent) -> CostEstimate {
    let mpp = spec.layout.metres_per_pixel;
    let smallest_m = match &spec.buildings.widths {
        Some(widths) => widths.iter().copied().fold(f64::INFINITY, f64::min),
        None if spec.facades.source == BUILTIN_FACADES => BUILTIN_MIN_WIDTH_M,
        None => FOLDER_MIN_WIDTH_M,
    };
    // As the placer rounds: at least one pixel.
    let width_px = (smallest_m / mpp).round().max(1.0);
    let gap_px = (spec.buildings.gap / mpp).round().max(0.0);
    let pitch = width_px + gap_px;
    let buildings = (layout.block_px as f64 / (pitch * pitch)).ceil() as u64;
    let spacing_px = (spec.lamps.spacing / mpp).max(1.0);
    let lamps = (2.0 * layout.line_px as f64 / spacing_px).ceil() as u64;
    let objects: u64 = spec.objects.iter().map(|o| u64::from(o.count)).sum();
    let pixels = layout.width * layout.height;
    let mut frame_memory = 0;
    let mut output = 0u64;
    let road_m = layout.line_px as f64 * mpp;
    for camera in &spec.cameras {
        let [w, h] = [0, 1].map(|i| u64::from(camera.resolution.get(i).copied().unwrap_or(1)));
        let ss = u64::from(camera.supersample);
        frame_memory = frame_memory.max(w * h * ss * ss * BYTES_PER_FRAME_SAMPLE);
        let frames = match camera.frame_rule() {
            FrameRule::Count(n) => u64::from(n),
            FrameRule::Spacing(s) => ((road_m / s) as u64).clamp(1, u64::from(MAX_FRAMES)),
        };
        output = output.saturating_add(frames * w * h * OUTPUT_BYTES_PER_FRAME_PIXEL);
    }
    let memory = BASE_BYTES
        .saturating_add(pixels.saturating_mul(BYTES_PER_PIXEL))
        .saturating_add(buildings.saturating_mul(BYTES_PER_BUILDING))
        .saturating_add(lamps.saturating_mul(BYTES_PER_LAMP))
        .saturating_add(objects.saturating_mul(BYTES_PER_OBJECT))
        .saturating_add(frame_memory);
    CostEstimate {
        pixels,
        buildings,
        lamps,
        objects,
        memory,
        output,
    }
}

/// Refuses a spec whose estimate exceeds the instance-id space or its `[limits]`.
pub(crate) fn check_costs(spec: &Spec, layout: LayoutExtent, findings: &mut Findings<'_, '_>) {
    let e = estimate(spec, layout);
    let parts = format!(
        "{} Mpx of layout, about {} buildings, {} lamps and {} inserted objects",
        mpx(e.pixels),
        e.buildings,
        e.lamps,
        e.objects
    );
    // The key most to blame: the largest contributor.
    let blame = {
        let candidates = [
            (
                e.buildings.saturating_mul(BYTES_PER_BUILDING),
                blame_buildings(findings),
            ),
            (e.lamps.saturating_mul(BYTES_PER_LAMP), "lamps.spacing"),
            (e.objects.saturating_mul(BYTES_PER_OBJECT), "objects"),
        ];
        candidates
            .iter()
            .max_by_key(|(n, _)| *n)
            .map_or("layout", |(_, key)| key)
    };
    if e.instances() > MAX_INSTANCE_ID {
        findings.error(
            blame,
            format!(
                "too many objects: the city would hold about {} objects ({parts}), over the \
                 {MAX_INSTANCE_ID} instance ids an ids image can tell apart; use larger \
                 `buildings.widths` or `gap`, a larger `lamps.spacing`, smaller `[[objects]]` \
                 counts or a smaller layout",
                e.instances()
            ),
        );
        return;
    }
    let limit = spec.limits.memory_mib.saturating_mul(1 << 20);
    if e.memory > limit {
        let mem_blame = if e.pixels.saturating_mul(BYTES_PER_PIXEL)
            > e.buildings
                .saturating_mul(BYTES_PER_BUILDING)
                .max(e.lamps.saturating_mul(BYTES_PER_LAMP))
                .max(e.objects.saturating_mul(BYTES_PER_OBJECT))
        {
            if findings.written("layout.mirror") {
                "layout.mirror"
            } else {
                "layout"
            }
        } else {
            blame
        };
        findings.error(
            mem_blame,
            format!(
                "too costly: the build would need about {} MiB of memory ({parts}), over the \
                 limit of {} MiB; raise `limits.memory_mib` if the machine has the memory, or \
                 make the city smaller",
                e.memory >> 20,
                spec.limits.memory_mib
            ),
        );
    }
    let limit = spec.limits.output_mib.saturating_mul(1 << 20);
    if e.output > limit {
        findings.error(
            "cameras",
            format!(
                "too many frame bytes: the cameras' frames would write about {} MiB (frames × \
                 resolution), over the limit of {} MiB; raise `limits.output_mib`, or take \
                 fewer or smaller frames",
                e.output >> 20,
                spec.limits.output_mib
            ),
        );
    }
}

fn blame_buildings(findings: &Findings<'_, '_>) -> &'static str {
    if findings.written("buildings.widths") {
        "buildings.widths"
    } else if findings.written("buildings.gap") {
        "buildings.gap"
    } else {
        "layout"
    }
}

fn mpx(pixels: u64) -> String {
    format!("{:.1}", pixels as f64 / 1e6)
}
