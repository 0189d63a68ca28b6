//! Blocks + roads → `sidewalk_NNNN` objects: the lamp strip around each block as a raised
//! slab ([`KERB_Y`] high) with vertical curb faces.
//!
//! The strip's width is measured from the layout ([`strip_width_px`]). A block's sidewalk
//! is its pixels grown by that width (square corners), clipped to the image, minus every
//! pixel already claimed: all blocks, all road rectangles, and the sidewalks of blocks with
//! lower ids. So no sidewalk overlaps a road, a block or another sidewalk.

use super::row_region::{RowRegion, subtract};
use super::{object, procedural};
use crate::model::ObjectKind;
use crate::model::geometry::{KERB_Y, MeshBuilder, RoadRect, strip_width_px};
use crate::model::{Band, ParsedLayout, SceneObject};

pub fn sidewalk_objects(layout: &ParsedLayout, mpp: f64, material: u32) -> Vec<SceneObject> {
    let (w, h) = (layout.width, layout.height);
    let strip = strip_width_px(layout);
    let mut claimed = RowRegion::new(w, h);
    for block in &layout.blocks {
        claimed.add_bands(&block.bands);
    }
    for road in &layout.roads {
        let r = RoadRect::of(road);
        claimed.add_rect(pixels(r.x), pixels(r.y));
    }
    let mut objects = Vec::new();
    for block in &layout.blocks {
        let ring = RowRegion::grown(w, h, &block.bands, strip).minus(&claimed);
        if ring.is_empty() {
            continue;
        }
        claimed.add_region(&ring);
        let mut top = MeshBuilder::new(material);
        slab(&mut top, &ring.bands(), mpp);
        objects.push(object(
            ObjectKind::Sidewalk,
            format!("sidewalk_{:04}", block.id),
            vec![top],
        ));
    }
    objects
}

/// The pixels a continuous `[a, b]` touches: `floor(a)..ceil(b)`, clamped at 0.
fn pixels(range: [f64; 2]) -> [u32; 2] {
    // `as` saturates: NaN → 0, beyond u32 → u32::MAX; the region clips to the image.
    [range[0].floor() as u32, range[1].ceil() as u32]
}

/// Top faces of `bands` at kerb height, and a curb face on every outside edge.
fn slab(mesh: &mut MeshBuilder, bands: &[Band], mpp: f64) {
    let tile = procedural::CONCRETE_TILE;
    let m = |v: u32| f64::from(v) * mpp;
    let ys = [0.0, KERB_Y];
    let v_span = [0.0, KERB_Y / tile];
    for (i, band) in bands.iter().enumerate() {
        let z = [m(band.y0), m(band.y1)];
        for &[x0, x1] in &band.spans {
            mesh.floor([m(x0), m(x1)], z, KERB_Y, tile);
            // Spans in a row never touch, so both ends are outside edges.
            let depth = [0.0, (z[1] - z[0]) / tile];
            mesh.wall(
                [m(x0), z[0]],
                [m(x0), z[1]],
                ys,
                [-1.0, 0.0, 0.0],
                depth,
                v_span,
            );
            mesh.wall(
                [m(x1), z[0]],
                [m(x1), z[1]],
                ys,
                [1.0, 0.0, 0.0],
                depth,
                v_span,
            );
        }
        let above = i
            .checked_sub(1)
            .map(|p| &bands[p])
            .filter(|p| p.y1 == band.y0)
            .map_or(&[][..], |p| &p.spans[..]);
        let below = bands
            .get(i + 1)
            .filter(|n| n.y0 == band.y1)
            .map_or(&[][..], |n| &n.spans[..]);
        for (neighbour, zz, nz) in [(above, z[0], -1.0), (below, z[1], 1.0)] {
            for [x0, x1] in subtract(&band.spans, neighbour) {
                let u = [0.0, (m(x1) - m(x0)) / tile];
                mesh.wall([m(x0), zz], [m(x1), zz], ys, [0.0, 0.0, nz], u, v_span);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::geometry::{cross, dot, sub};

    #[test]
    fn a_ring_slab_has_a_top_and_curbs_on_both_rims() {
        // A 10 × 10 px ring around a 4 × 4 hole: three bands.
        let bands = vec![
            Band {
                y0: 0,
                y1: 3,
                spans: vec![[0, 10]],
            },
            Band {
                y0: 3,
                y1: 7,
                spans: vec![[0, 3], [7, 10]],
            },
            Band {
                y0: 7,
                y1: 10,
                spans: vec![[0, 10]],
            },
        ];
        let mut mesh = MeshBuilder::new(0);
        slab(&mut mesh, &bands, 1.0);
        let mesh = mesh.finish();
        let (mut top, mut outer, mut inner) = (0.0, 0.0, 0.0);
        for t in 0..mesh.indices.len() / 3 {
            let p = |k: usize| mesh.positions[mesh.indices[3 * t + k] as usize].map(f64::from);
            let n = cross(sub(p(1), p(0)), sub(p(2), p(0)));
            let area = dot(n, n).sqrt() / 2.0;
            if n[1] > 0.0 {
                top += area;
                continue;
            }
            assert_eq!(n[1], 0.0);
            // Outward from the ring: away from the centre on the rim, towards it in the hole.
            let c = [
                (p(0)[0] + p(1)[0] + p(2)[0]) / 3.0,
                (p(0)[2] + p(1)[2] + p(2)[2]) / 3.0,
            ];
            let out = n[0] * (c[0] - 5.0) + n[2] * (c[1] - 5.0);
            let on_rim = c[0] <= 0.0 || c[0] >= 10.0 || c[1] <= 0.0 || c[1] >= 10.0;
            if on_rim {
                assert!(out > 0.0, "triangle {t}");
                outer += area;
            } else {
                assert!(out < 0.0, "triangle {t}");
                inner += area;
            }
        }
        assert!((top - 84.0).abs() < 1e-4, "{top}");
        assert!((outer - 40.0 * KERB_Y).abs() < 1e-4, "{outer}");
        assert!((inner - 16.0 * KERB_Y).abs() < 1e-4, "{inner}");
    }
}
