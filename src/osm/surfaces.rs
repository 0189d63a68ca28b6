//! The street surface as polygons (`i_overlay`): carriageways, sidewalks and the blocks
//! between them.
//!
//! Each paved segment's carriageway is its centreline stroked to its fitted width with
//! round caps, so consecutive segments join round and crossing roads merge into one
//! junction; the union of all of them, cut to the box, is the carriageway. Each sidewalk is the strip
//! beside its segment's carriageway on its side, with a disc at every joint as wide as the
//! narrower of the segment's two sidewalks (filling the outside of bends); the union of
//! those cut to the box, less the carriageway, is the sidewalks. The blocks are the box less
//! both; a block under [`MIN_BLOCK`] (a sliver between strips) is paved as sidewalk.
//!
//! The open ground is the union of the map's green areas (`tags::green`), and of its
//! squares (`tags::square`) less the green, cut to each block: it never lies on the
//! street, and each piece belongs to one block. The paths across it are the map's
//! footways, paths, cycleways, bridleways and tracks on the ground (`tags::ground_path`)
//! stroked to their widths, where they cross the green.

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::overlay::FloatOverlay;
use i_overlay::mesh::float::stroke::offset::StrokeOffset;
use i_overlay::mesh::float::style::{LineCap, LineJoin, StrokeStyle};

use crate::model::geometry::polygon::{bounds, left_normal};
use crate::model::geometry::polygon_set::{Contours, intersection, polygons};
use crate::model::{MapArea, MapPolygon, MapRoad};

/// Radians an arc's segments turn: 24 to a full circle.
const ARC_STEP: f64 = std::f64::consts::PI / 12.0;

/// The smallest block, square metres: anything smaller left between the street's surfaces
/// is paved as sidewalk.
pub const MIN_BLOCK: f64 = 4.0;

/// The smallest piece of open ground kept, square metres.
pub const MIN_OPEN: f64 = 1.0;

/// Carriageway, sidewalks and blocks of `roads` inside `extent`.
pub fn surfaces(roads: &[MapRoad], extent: [f64; 4]) -> [Vec<MapPolygon>; 3] {
    let mut carriageway: Contours = Vec::new();
    let mut sidewalks: Contours = Vec::new();
    for road in roads.iter().filter(|r| r.surface) {
        for (w, &[width, left, right]) in road.centreline.windows(2).zip(&road.fitted) {
            if width <= 0.0 {
                continue;
            }
            let (a, b) = (w[0], w[1]);
            let style = StrokeStyle::new(width)
                .start_cap(LineCap::Round(ARC_STEP))
                .end_cap(LineCap::Round(ARC_STEP));
            for shape in [a, b].stroke(style, false) {
                carriageway.extend(shape);
            }
            let Some(n) = left_normal(a, b) else {
                continue;
            };
            let at = |p: [f64; 2], s: f64| [p[0] + n[0] * s, p[1] + n[1] * s];
            let half = width / 2.0;
            for (inner, outer) in [(half, half + left), (-half - right, -half)] {
                if outer > inner {
                    sidewalks.push(vec![at(a, inner), at(b, inner), at(b, outer), at(a, outer)]);
                }
            }
            let round = left.min(right);
            if round > 0.0 {
                let style = StrokeStyle::new(width + 2.0 * round)
                    .start_cap(LineCap::Round(ARC_STEP))
                    .end_cap(LineCap::Round(ARC_STEP));
                for shape in [a, a]
                    .stroke(style.clone(), false)
                    .into_iter()
                    .chain([b, b].stroke(style, false))
                {
                    sidewalks.extend(shape);
                }
            }
        }
    }
    let [x0, z0, x1, z1] = extent;
    let bounds = vec![[x0, z0], [x1, z0], [x1, z1], [x0, z1]];
    // Both cut to the box: round caps reach past its edge.
    let carriageway_shapes = FloatOverlay::with_subj_and_clip(&carriageway, &bounds)
        .overlay(OverlayRule::Intersect, FillRule::NonZero);
    let carriageway_flat: Contours = carriageway_shapes.iter().flatten().cloned().collect();
    let sidewalks_inside: Contours = FloatOverlay::with_subj_and_clip(&sidewalks, &bounds)
        .overlay(OverlayRule::Intersect, FillRule::NonZero)
        .into_iter()
        .flatten()
        .collect();
    let sidewalk_shapes = FloatOverlay::with_subj_and_clip(&sidewalks_inside, &carriageway_flat)
        .overlay(OverlayRule::Difference, FillRule::NonZero);
    let mut street: Contours = carriageway_flat.clone();
    street.extend(sidewalk_shapes.iter().flatten().cloned());
    let block_shapes = FloatOverlay::with_subj_and_clip(&bounds, &street)
        .overlay(OverlayRule::Difference, FillRule::NonZero);
    let [carriageway, mut sidewalks, blocks] =
        [carriageway_shapes, sidewalk_shapes, block_shapes].map(polygons);
    // Slivers the strips leave between them (at bends, where sidewalks meet at a
    // junction) are pavement, not blocks.
    let (blocks, slivers): (Vec<_>, Vec<_>) = blocks.into_iter().partition(|b| b.area >= MIN_BLOCK);
    sidewalks.extend(slivers);
    [carriageway, sidewalks, blocks]
}

/// The open ground on `blocks`: the union of the `green` areas, and the union of the
/// `squares` less the green (a lawn mapped on a square is grass), each cut to each
/// block, in block order (each its outer ring then its holes); pieces under
/// [`MIN_OPEN`] dropped. Third, the `paths` across the green: each path's centreline
/// stroked to its width with round ends, their union cut to the green and to each block.
pub fn open_ground(
    green: &[Contours],
    squares: &[Contours],
    paths: &[&MapRoad],
    blocks: &[MapPolygon],
) -> [Vec<MapArea>; 3] {
    // Non-zero fill: an area's hole cancels its own outer ring only, so a point is open
    // when any area holds it.
    let union = |areas: &[Contours]| -> Contours {
        FloatOverlay::with_subj(&areas.concat())
            .overlay(OverlayRule::Subject, FillRule::NonZero)
            .concat()
    };
    let green = union(green);
    let squares: Contours = FloatOverlay::with_subj_and_clip(&union(squares), &green)
        .overlay(OverlayRule::Difference, FillRule::NonZero)
        .concat();
    let mut strokes: Contours = Vec::new();
    for road in paths.iter().filter(|r| r.width > 0.0) {
        let style = StrokeStyle::new(road.width)
            .start_cap(LineCap::Round(ARC_STEP))
            .end_cap(LineCap::Round(ARC_STEP))
            .line_join(LineJoin::Round(ARC_STEP));
        for shape in road.centreline.stroke(style, false) {
            strokes.extend(shape);
        }
    }
    let paths: Contours = FloatOverlay::with_subj_and_clip(&union(&[strokes]), &green)
        .overlay(OverlayRule::Intersect, FillRule::NonZero)
        .concat();
    [
        on_blocks(&green, blocks),
        on_blocks(&squares, blocks),
        on_blocks(&paths, blocks),
    ]
}

/// The shapes of `union` (rings from an overlay, non-zero) cut to each block.
fn on_blocks(union: &Contours, blocks: &[MapPolygon]) -> Vec<MapArea> {
    let boxes: Vec<[f64; 4]> = union.iter().map(|ring| bounds(ring)).collect();
    let mut out = Vec::new();
    for (n, block) in blocks.iter().enumerate() {
        let b = bounds(&block.outer);
        // Rings whose box meets the block's: a hole always comes with its outer ring,
        // whose box holds the hole's.
        let near: Contours = union
            .iter()
            .zip(&boxes)
            .filter(|(_, g)| g[0] < b[2] && b[0] < g[2] && g[1] < b[3] && b[1] < g[3])
            .map(|(ring, _)| ring.clone())
            .collect();
        if near.is_empty() {
            continue;
        }
        out.extend(
            intersection(block, &near)
                .into_iter()
                .filter(|p| p.area >= MIN_OPEN)
                .map(|shape| MapArea {
                    block: n as u32,
                    shape,
                }),
        );
    }
    out
}
