//! A map building → the volumes the city builds it of (Simple 3D Buildings): the scene
//! builds each one, and wall text keeps below the eaves of what stands along its wall
//! ([`ground_eave`]).
//!
//! | building | volumes |
//! |---|---|
//! | without parts | its footprint, from its `min_height` (else the ground) up to its height, with its roof ([`shaped`]) |
//! | with parts ([`MapBuilding::parts`]) | each part, from its own `min_height` up to its own height (else the building's), with its own roof; and the rest of the footprint (less the parts that stand on the ground), as the building, with the building's roof where its shape fits a piece |
//!
//! So a part that starts on an upper floor stands on the rest of the building, a part
//! taller than the building rises out of it, and one lower shows as a step. A part whose
//! own height the map does not give, starting above the building's height (a dome on a
//! tower), has no walls: its roof rises from its `min_height`.

use super::polygon::{contains, ring_distance};
use super::polygon_set::difference;
use super::roofs::{Mass, Roof, shaped};
use crate::model::{MapBuilding, MapPolygon};

/// The smallest piece of a building's footprint left beside its parts that the city
/// builds, square metres: smaller ones are slivers between rings drawn almost alike.
pub const MIN_PIECE: f64 = 1.0;
/// How close to a volume's ring a point on a wall counts as on that volume, metres.
const ON_RING: f64 = 0.1;
/// How finely [`ground_eave`] follows a wall, metres.
const STEP: f64 = 0.5;

/// One volume of a building: a footprint extruded from `base` to `eave`, then its roof.
#[derive(Clone, Debug, PartialEq)]
pub struct Volume {
    /// Counter-clockwise in `[x, z]` (positive area), without repeating its first point.
    pub outer: Vec<[f64; 2]>,
    /// Clockwise.
    pub holes: Vec<Vec<[f64; 2]>>,
    /// Where its walls start, metres above the ground.
    pub base: f64,
    /// Where its walls stop (its roof's foot), metres above the ground.
    pub eave: f64,
    pub roof: Option<Roof>,
}

/// The volumes of map building `b`, `height` tall (its cladding's: the map's, else
/// seeded), in the order the module's table gives: the rest of its footprint, then its
/// parts. Pure and deterministic.
pub fn volumes(b: &MapBuilding, height: f64) -> Vec<Volume> {
    if b.parts.is_empty() {
        return vec![volume(Mass::of(b), b.min_height, height)];
    }
    let ground: Vec<MapPolygon> = (b.parts.iter())
        .filter(|p| p.min_height.is_none())
        .map(|p| MapPolygon {
            outer: p.outer.clone(),
            holes: p.holes.clone(),
            area: p.area,
        })
        .collect();
    let footprint = MapPolygon {
        outer: b.outer.clone(),
        holes: b.holes.clone(),
        area: b.area,
    };
    let cut: Vec<&MapPolygon> = ground.iter().collect();
    let mut out: Vec<Volume> = difference(&footprint, &cut)
        .iter()
        .filter(|piece| piece.area >= MIN_PIECE)
        .map(|piece| {
            let mass = Mass {
                outer: &piece.outer,
                holes: &piece.holes,
                ..Mass::of(b)
            };
            volume(mass, b.min_height, height)
        })
        .collect();
    for p in &b.parts {
        let base = p.min_height.unwrap_or(0.0);
        let (top, mapped_top) = match p.height {
            Some(h) => (h, p.height_from == "height"),
            None => (height.max(base), b.height_from == "height" && height > base),
        };
        let mass = Mass {
            top: mapped_top,
            ..Mass::of(p)
        };
        out.push(volume(mass, p.min_height, top));
    }
    out
}

/// `m` from `min` (else the ground) up to `top` above the ground (at least its base).
fn volume(m: Mass, min: Option<f64>, top: f64) -> Volume {
    let base = min.unwrap_or(0.0);
    let (walls, roof) = shaped(&m, (top - base).max(0.0));
    Volume {
        outer: m.outer.to_vec(),
        holes: m.holes.to_vec(),
        base,
        eave: base + walls,
        roof,
    }
}

/// The lowest eave of the volumes that stand on the ground along the wall `a → b` (a
/// footprint edge, `inward` the unit normal into the building), followed every
/// half a metre; 0 where a stretch of it has none (the building is lifted there).
pub fn ground_eave(volumes: &[Volume], a: [f64; 2], b: [f64; 2], inward: [f64; 2]) -> f64 {
    if let [only] = volumes {
        return if only.base <= 0.0 { only.eave } else { 0.0 };
    }
    let ground: Vec<&Volume> = volumes.iter().filter(|v| v.base <= 0.0).collect();
    let length = super::polygon::distance(a, b);
    let steps = ((length / STEP).ceil() as usize).max(1);
    let mut lowest = f64::INFINITY;
    for k in 0..steps {
        let t = (k as f64 + 0.5) / steps as f64;
        let p = [
            a[0] + (b[0] - a[0]) * t + inward[0] * ON_RING / 2.0,
            a[1] + (b[1] - a[1]) * t + inward[1] * ON_RING / 2.0,
        ];
        let on = (ground.iter()).filter(|v| {
            let inside = contains(&v.outer, p) && !v.holes.iter().any(|h| contains(h, p));
            inside || ring_distance(&v.outer, p) < ON_RING
        });
        let eave = on.map(|v| v.eave).fold(f64::INFINITY, f64::min);
        if eave.is_infinite() {
            return 0.0;
        }
        lowest = lowest.min(eave);
    }
    lowest
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::OsmElement;

    /// An axis-aligned footprint `x0…x1` × `z0…z1`, counter-clockwise in `[x, z]`.
    fn rect(x0: f64, z0: f64, x1: f64, z1: f64) -> Vec<[f64; 2]> {
        vec![[x0, z0], [x1, z0], [x1, z1], [x0, z1]]
    }

    fn building(id: i64, outer: Vec<[f64; 2]>, height: Option<f64>) -> MapBuilding {
        MapBuilding {
            height,
            height_from: if height.is_some() { "levels" } else { "none" }.to_owned(),
            ..MapBuilding::new(OsmElement::Way(id), 0, outer, Vec::new())
        }
    }

    #[test]
    fn a_building_without_parts_is_one_volume_from_its_min_height() {
        let mut b = building(1, rect(0.0, 0.0, 20.0, 10.0), Some(12.0));
        let v = volumes(&b, 12.0);
        assert_eq!(v.len(), 1);
        assert_eq!(
            (v[0].base, v[0].eave, v[0].outer.clone()),
            (0.0, 12.0, b.outer.clone())
        );
        // A canopy 2.5 m up.
        b.min_height = Some(2.5);
        let v = volumes(&b, 4.0);
        assert_eq!((v[0].base, v[0].eave), (2.5, 4.0));
        // Nothing of it stands on the ground: no wall for text.
        assert_eq!(ground_eave(&v, [0.0, 0.0], [20.0, 0.0], [0.0, 1.0]), 0.0);
    }

    #[test]
    fn parts_stand_on_the_rest_of_the_building() {
        // A 20 × 10 m building 12 m tall; a 30 m tower on its west quarter; a storey from
        // 6 to 18 m over its east half; a dome from 20 m up without a height of its own.
        let mut b = building(1, rect(0.0, 0.0, 20.0, 10.0), Some(12.0));
        let mut tower = building(2, rect(0.0, 0.0, 5.0, 10.0), Some(30.0));
        tower.height_from = "height".to_owned();
        let mut storey = building(3, rect(10.0, 0.0, 20.0, 10.0), Some(18.0));
        storey.min_height = Some(6.0);
        let mut dome = building(4, rect(1.0, 1.0, 4.0, 4.0), None);
        dome.min_height = Some(20.0);
        dome.roof_shape = Some("dome".to_owned());
        dome.roof_height = Some(3.0);
        b.parts = vec![tower, storey, dome];
        let v = volumes(&b, 12.0);
        assert_eq!(v.len(), 4, "{v:?}");
        // The rest: the footprint less the tower (the storey is lifted), 12 m tall.
        let rest = &v[0];
        assert!((super::super::polygon::signed_area(&rest.outer) - 150.0).abs() < 1e-9);
        assert_eq!((rest.base, rest.eave), (0.0, 12.0));
        assert_eq!((v[1].base, v[1].eave), (0.0, 30.0));
        assert_eq!((v[2].base, v[2].eave), (6.0, 18.0));
        // The dome has no walls; its roof rises its 3 m from 20 m.
        assert_eq!((v[3].base, v[3].eave), (20.0, 20.0));
        assert_eq!(v[3].roof.as_ref().map(|r| r.rise), Some(3.0));
        // Along the south wall (z = 0, inward +z) the tower and the rest stand on the
        // ground: the lower eave, 12 m. Along the tower's own west wall, 30 m.
        let inward = [0.0, 1.0];
        assert_eq!(ground_eave(&v, [0.0, 0.0], [20.0, 0.0], inward), 12.0);
        assert_eq!(ground_eave(&v, [0.0, 10.0], [0.0, 0.0], [1.0, 0.0]), 30.0);
        // With the building lifted 3 m, the east half stands on nothing: no text there.
        b.min_height = Some(3.0);
        let v = volumes(&b, 12.0);
        assert_eq!(ground_eave(&v, [10.0, 0.0], [20.0, 0.0], inward), 0.0);
        assert_eq!(ground_eave(&v, [0.0, 10.0], [0.0, 0.0], [1.0, 0.0]), 30.0);
    }
}
