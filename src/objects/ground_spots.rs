//! Roads + blocks + lamps → random free spots on the strips beside the roads and in the
//! right-hand lanes, each with the direction of the traffic passing it.
//!
//! Traffic keeps right: on a horizontal road the lane below the centre line (larger image
//! y) runs east. A strip spot is mid-strip beside a road, off every road (so never in a
//! crossing) with a block pixel just behind it; a lane spot is mid-lane, clear of every
//! other road by the object's radius. Spots keep [`LAMP_CLEARANCE`] plus their radius from
//! lamps and their radius plus theirs from every spot taken before.

mod ways;

pub use ways::CrossingSpot;

use rand::RngExt;
use rand_pcg::Pcg64;

use super::ObjectsInput;
use super::footprint_grid::FootprintGrid;
use crate::model::geometry::zebras::road_stretches;
use crate::model::geometry::{RoadRect, strip_width_px};
use crate::model::{Axis, ParsedLayout, Road};

/// Metres an object keeps from a lamp site.
pub const LAMP_CLEARANCE: f64 = 2.0;

/// Side of the buckets footprints are found by, metres: about a car's length, the size of
/// most footprints.
pub const GRID_CELL: f64 = 8.0;

/// A chosen spot, in metres (x east, z south).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spot {
    pub position: [f64; 2],
    /// Unit direction of the traffic in the nearest lane of the road (x, z).
    pub travel: [f64; 2],
    pub road: u32,
}

/// Where objects already stand, and the geometry spots are drawn from.
pub struct GroundSpots<'a> {
    layout: &'a ParsedLayout,
    rects: Vec<RoadRect>,
    mpp: f64,
    strip_px: f64,
    /// The ground everything standing takes, in metres: lamps first, with
    /// [`LAMP_CLEARANCE`] as their radius.
    taken: FootprintGrid,
    /// Every zebra crossing: its road's index and its along-axis range, metres.
    zebras: Vec<(usize, [f64; 2])>,
    /// The footprints of people walking along strips (indices in `taken`, ascending): in
    /// no one's way, as they move on.
    walkers: Vec<usize>,
}

/// A street corner, in metres (x east, z south), and the horizontal and vertical road that
/// meet there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    pub position: [f64; 2],
    pub roads: [u32; 2],
    /// Which side of the crossing the corner is on: −1 or 1 along x (west, east of the
    /// vertical road) and along z (north, south of the horizontal road).
    pub sides: [f64; 2],
}

/// Ground an object takes, in metres (x east, z south).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Footprint {
    /// Centre (x, z) and radius.
    Circle([f64; 2], f64),
    /// An axis-aligned rectangle `[x0, x1] × [z0, z1]` (cars: roads are axis-aligned).
    Rect([f64; 2], [f64; 2]),
}

impl Footprint {
    /// Whether the two share interior area (touching does not count).
    pub fn overlaps(&self, other: &Footprint) -> bool {
        match (*self, *other) {
            (Footprint::Circle(a, ra), Footprint::Circle(b, rb)) => {
                let (dx, dz) = (a[0] - b[0], a[1] - b[1]);
                dx * dx + dz * dz < (ra + rb) * (ra + rb)
            }
            (Footprint::Circle(c, r), Footprint::Rect(x, z))
            | (Footprint::Rect(x, z), Footprint::Circle(c, r)) => {
                let dx = c[0] - c[0].clamp(x[0], x[1]);
                let dz = c[1] - c[1].clamp(z[0], z[1]);
                dx * dx + dz * dz < r * r
            }
            (Footprint::Rect(ax, az), Footprint::Rect(bx, bz)) => {
                ax[0] < bx[1] && bx[0] < ax[1] && az[0] < bz[1] && bz[0] < az[1]
            }
        }
    }
}

/// Where on a road a footprint goes: its half extents along and across the road and its
/// distance right of the centre line (driving direction), in metres, how far it keeps
/// from every other road (a crossing) and, along the road, from other footprints, and
/// whether it is a vehicle parked at the kerb (a map keeps those off the kerbs its
/// parking tags forbid).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoadSlot {
    pub half: [f64; 2],
    pub offset: f64,
    pub crossing_clearance: f64,
    pub gap: f64,
    pub parked: bool,
}

/// Where a vehicle may stand on a road: a layout's roads ([`GroundSpots`]) or a map's
/// (`map_spots::MapSpots`).
pub trait RoadSpots {
    /// A random road, side and place along it where `slot` fits (given the road's width
    /// in metres), clear of other roads and of everything taken; the footprint is taken.
    /// None after `attempts`.
    fn road(
        &mut self,
        rng: &mut Pcg64,
        attempts: u32,
        slot: impl Fn(f64) -> Option<RoadSlot>,
    ) -> Option<Spot>;
}

/// Where people and parked bicycles stand beside the roads: a layout's sidewalk strips
/// ([`GroundSpots`]) or a map's sidewalks (`map_objects::MapSpots`).
pub trait StripSpots: RoadSpots {
    /// A free sidewalk spot for an object of `radius` metres, `from_curb(w)` metres from
    /// the kerb of a sidewalk `w` metres wide (a layout's strips are all one width), or
    /// None after `attempts`. Its `travel` is the traffic's in the lane nearest to it.
    fn strip_at(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        from_curb: impl Fn(f64) -> f64,
        attempts: u32,
    ) -> Option<Spot>;

    /// A free spot on a zebra crossing for a person crossing it, its way over taken
    /// ([`GroundSpots::zebra`]; a map's: `MapSpots::zebra`). None where there is no zebra,
    /// or after `attempts`.
    fn zebra(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        reach: f64,
        beyond: f64,
        attempts: u32,
    ) -> Option<CrossingSpot>;

    /// A free spot at a zebra's end for a person waiting to cross, its way over taken
    /// ([`GroundSpots::zebra_kerb`]; a map's: `MapSpots::zebra_kerb`). None where there is
    /// no zebra, or after `attempts`.
    fn zebra_kerb(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        from_curb: f64,
        attempts: u32,
    ) -> Option<CrossingSpot>;

    /// A free spot on a path across a park for an object of `radius` metres, its centre
    /// `radius` inside the path's edges and its `travel` along the path
    /// (`MapSpots::park`). None where there is no such path, or after `attempts`.
    fn park(&mut self, rng: &mut Pcg64, radius: f64, attempts: u32) -> Option<Spot>;

    /// A free spot on a square or pedestrian area for an object of `radius` metres, its
    /// centre `radius` inside the square's edges, its `travel` drawn (`MapSpots::square`).
    /// None where there is no such square, or after `attempts`.
    fn square(&mut self, rng: &mut Pcg64, radius: f64, attempts: u32) -> Option<Spot>;

    /// Marks the footprint taken last as a person walking along a sidewalk, out of the
    /// way of the others' walks ([`GroundSpots::free_run`]).
    fn mark_walker(&mut self);
}

impl StripSpots for GroundSpots<'_> {
    fn strip_at(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        from_curb: impl Fn(f64) -> f64,
        attempts: u32,
    ) -> Option<Spot> {
        let from_curb = from_curb(2.0 * self.strip_half());
        GroundSpots::strip_at(self, rng, radius, from_curb, attempts)
    }

    fn zebra(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        reach: f64,
        beyond: f64,
        attempts: u32,
    ) -> Option<CrossingSpot> {
        GroundSpots::zebra(self, rng, radius, reach, beyond, attempts)
    }

    fn zebra_kerb(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        from_curb: f64,
        attempts: u32,
    ) -> Option<CrossingSpot> {
        GroundSpots::zebra_kerb(self, rng, radius, from_curb, attempts)
    }

    /// A layout has no parks (its blocks are built on or paved), so no paths across them.
    fn park(&mut self, _: &mut Pcg64, _: f64, _: u32) -> Option<Spot> {
        None
    }

    /// A layout's open paving takes trees only (`tree::plaza_spot`), not people yet.
    fn square(&mut self, _: &mut Pcg64, _: f64, _: u32) -> Option<Spot> {
        None
    }

    fn mark_walker(&mut self) {
        GroundSpots::mark_walker(self)
    }
}

impl RoadSpots for GroundSpots<'_> {
    fn road(
        &mut self,
        rng: &mut Pcg64,
        attempts: u32,
        slot: impl Fn(f64) -> Option<RoadSlot>,
    ) -> Option<Spot> {
        GroundSpots::road(self, rng, attempts, slot)
    }
}

impl<'a> GroundSpots<'a> {
    pub fn new(input: &'a ObjectsInput) -> Self {
        let mpp = input.metres_per_pixel;
        GroundSpots {
            layout: input.layout,
            rects: input.layout.roads.iter().map(RoadRect::of).collect(),
            mpp,
            strip_px: f64::from(strip_width_px(input.layout)),
            taken: input
                .lamps
                .iter()
                .fold(FootprintGrid::new(GRID_CELL), |mut taken, l| {
                    taken.push(Footprint::Circle(
                        [l.position[0] * mpp, l.position[1] * mpp],
                        LAMP_CLEARANCE,
                    ));
                    taken
                }),
            zebras: road_stretches(input.layout, mpp)
                .into_iter()
                .enumerate()
                .flat_map(|(i, s)| s.zebras.into_iter().map(move |(along, _)| (i, along)))
                .collect(),
            walkers: Vec::new(),
        }
    }

    /// Half the strip's width, in metres.
    pub fn strip_half(&self) -> f64 {
        self.strip_px / 2.0 * self.mpp
    }

    /// Marks the footprint taken last as a person walking along a strip's.
    pub fn mark_walker(&mut self) {
        if let Some(last) = self.taken.footprints().len().checked_sub(1) {
            self.walkers.push(last);
        }
    }

    /// Gives back the ground `spot` took (the last taken): its caller found it unfit.
    pub fn release(&mut self, spot: Spot) {
        let last = self.taken.last();
        if matches!(last, Some(Footprint::Circle(p, _)) if *p == spot.position) {
            self.taken.pop();
        }
    }

    /// Takes `footprint` if it overlaps nothing taken; whether it did.
    pub fn claim(&mut self, footprint: Footprint) -> bool {
        if self.taken.overlaps(&footprint) {
            return false;
        }
        self.taken.push(footprint);
        true
    }

    /// A random road (uniform), side and place along it where `slot` fits: wholly on the
    /// road, `slot.crossing_clearance` clear of every other road, overlapping nothing taken
    /// (`slot.gap` added along the road). `offset` says where across, given the road's
    /// width in metres; None skips the draw. The footprint is taken. None after `attempts`.
    pub fn road(
        &mut self,
        rng: &mut Pcg64,
        attempts: u32,
        slot: impl Fn(f64) -> Option<RoadSlot>,
    ) -> Option<Spot> {
        (0..attempts).find_map(|_| {
            let (road, high, along) = self.pick_road(rng)?;
            let s = slot((road.edges[1] - road.edges[0]) * self.mpp)?;
            let right = if high { 1.0 } else { -1.0 };
            let across = road.line + right * s.offset / self.mpp;
            let [ha, hc] = s.half.map(|h| h / self.mpp);
            let own = RoadRect::of(road);
            let (a, c) = match road.axis {
                Axis::Horizontal => (own.x, own.y),
                Axis::Vertical => (own.y, own.x),
            };
            let on_own = a[0] <= along - ha
                && along + ha <= a[1]
                && c[0] <= across - hc
                && across + hc <= c[1];
            let clear = s.crossing_clearance / self.mpp;
            let rect = |ga: f64| {
                let (x, z) = match road.axis {
                    Axis::Horizontal => (
                        [along - ha - ga, along + ha + ga],
                        [across - hc, across + hc],
                    ),
                    Axis::Vertical => (
                        [across - hc, across + hc],
                        [along - ha - ga, along + ha + ga],
                    ),
                };
                RoadRect { x, y: z }
            };
            let grown = rect(clear);
            let clear_of_others = self
                .rects
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != road.id as usize)
                .all(|(_, r)| !r.overlaps(&grown));
            if !on_own || !clear_of_others {
                return None;
            }
            let metres =
                |r: RoadRect| Footprint::Rect(r.x.map(|v| v * self.mpp), r.y.map(|v| v * self.mpp));
            let probe = metres(rect(s.gap / self.mpp));
            if self.taken.overlaps(&probe) {
                return None;
            }
            self.taken.push(metres(rect(0.0)));
            let px = image_point(road, along, across);
            Some(Spot {
                position: [px[0] * self.mpp, px[1] * self.mpp],
                travel: travel(road.axis, high),
                road: road.id,
            })
        })
    }

    /// A free mid-strip spot for an object of `radius` metres, or None after `attempts`.
    pub fn strip(&mut self, rng: &mut Pcg64, radius: f64, attempts: u32) -> Option<Spot> {
        let mid = self.strip_half();
        self.strip_at(rng, radius, mid, attempts)
    }

    /// A free strip spot `from_curb` metres from the curb for an object of `radius`
    /// metres, or None after `attempts`.
    pub fn strip_at(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        from_curb: f64,
        attempts: u32,
    ) -> Option<Spot> {
        let strip = self.strip_px;
        let offset = from_curb / self.mpp;
        (0..attempts).find_map(|_| {
            let (road, high, along) = self.pick_road(rng)?;
            let across = if high {
                road.edges[1] + offset
            } else {
                road.edges[0] - offset
            };
            let px = image_point(road, along, across);
            // One pixel past the strip's far edge must be a block: a real strip, not a gap.
            let beyond = strip - offset + 1.0;
            let behind = image_point(road, along, across + if high { beyond } else { -beyond });
            if !self.inside_image(px) || self.on_road(px, 0.0) || !self.in_block(behind) {
                return None;
            }
            self.take(road, high, px, radius)
        })
    }

    /// The free mid-strip spot beside road `road` at `along` metres along its axis, on
    /// its `high` side, for an object of `radius` metres; None where that is no strip
    /// (on a road, past the image, a road just behind: no strip that wide) or the ground
    /// is taken. At a corner the strip runs on into the crossing road's: that counts.
    pub fn strip_beside(&mut self, road: u32, high: bool, along: f64, radius: f64) -> Option<Spot> {
        let road = self.layout.roads.iter().find(|r| r.id == road)?;
        let offset = self.strip_px / 2.0;
        let across = if high {
            road.edges[1] + offset
        } else {
            road.edges[0] - offset
        };
        let along = along / self.mpp;
        let px = image_point(road, along, across);
        let beyond = self.strip_px - offset + 1.0;
        let behind = image_point(road, along, across + if high { beyond } else { -beyond });
        if !along.is_finite()
            || !self.inside_image(px)
            || !self.inside_image(behind)
            || self.on_road(px, 0.0)
            || self.on_road(behind, 0.0)
        {
            return None;
        }
        self.take(road, high, px, radius)
    }

    /// A free spot in the middle of a right-hand lane, or None after `attempts`.
    pub fn lane(&mut self, rng: &mut Pcg64, radius: f64, attempts: u32) -> Option<Spot> {
        (0..attempts).find_map(|_| {
            let (road, high, along) = self.pick_road(rng)?;
            let quarter = (road.edges[1] - road.edges[0]) / 4.0;
            let across = if high {
                road.line + quarter
            } else {
                road.line - quarter
            };
            let px = image_point(road, along, across);
            let r_px = radius / self.mpp;
            let clear_of_others = self
                .rects
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != road.id as usize)
                .all(|(_, r)| !within(r, px, r_px));
            // The whole footprint stays on this road: along and across.
            let in_own = road.start + r_px <= along
                && along <= road.end - r_px
                && road.edges[0] <= across - r_px
                && across + r_px <= road.edges[1];
            if !self.inside_image(px) || !clear_of_others || !in_own {
                return None;
            }
            self.take(road, high, px, radius)
        })
    }

    /// The street corners: where the strips of a horizontal and a vertical road that cross
    /// (or meet) touch, half a strip from both curbs, with a block pixel diagonally behind.
    /// In (horizontal road, vertical road, north-west, north-east, south-west, south-east)
    /// order. Nothing is taken.
    pub fn corners(&self) -> Vec<Corner> {
        let roads = &self.layout.roads;
        let half = self.strip_px / 2.0;
        let mut out = Vec::new();
        for h in roads.iter().filter(|r| r.axis == Axis::Horizontal) {
            for v in roads.iter().filter(|r| r.axis == Axis::Vertical) {
                let (hr, vr) = (&self.rects[h.id as usize], &self.rects[v.id as usize]);
                if !hr.overlaps(vr) {
                    continue;
                }
                for (sz, sx) in [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)] {
                    let x = if sx < 0.0 {
                        vr.x[0] - half
                    } else {
                        vr.x[1] + half
                    };
                    let z = if sz < 0.0 {
                        hr.y[0] - half
                    } else {
                        hr.y[1] + half
                    };
                    let behind = [x + sx * (half + 1.0), z + sz * (half + 1.0)];
                    if self.inside_image([x, z])
                        && !self.on_road([x, z], 0.0)
                        && self.in_block(behind)
                    {
                        out.push(Corner {
                            position: [x * self.mpp, z * self.mpp],
                            roads: [h.id, v.id],
                            sides: [sx, sz],
                        });
                    }
                }
            }
        }
        out
    }

    /// [`GroundSpots::corners`] in a random order (Fisher–Yates from `rng`): which corners
    /// a pole entry tries first.
    pub fn shuffled_corners(&self, rng: &mut Pcg64) -> Vec<Corner> {
        let mut corners = self.corners();
        for i in (1..corners.len()).rev() {
            corners.swap(i, rng.random_range(0..=i));
        }
        corners
    }

    /// A road (uniform among the roads), a side and an along-position on it.
    fn pick_road(&self, rng: &mut Pcg64) -> Option<(&'a Road, bool, f64)> {
        let roads = &self.layout.roads;
        if roads.is_empty() {
            return None;
        }
        let road = &roads[rng.random_range(0..roads.len())];
        let high: bool = rng.random();
        let t: f64 = rng.random();
        let along = road.start + t * (road.end - road.start);
        along.is_finite().then_some((road, high, along))
    }

    fn take(&mut self, road: &Road, high: bool, px: [f64; 2], radius: f64) -> Option<Spot> {
        let position = [px[0] * self.mpp, px[1] * self.mpp];
        if !self.claim(Footprint::Circle(position, radius)) {
            return None;
        }
        Some(Spot {
            position,
            travel: travel(road.axis, high),
            road: road.id,
        })
    }

    fn inside_image(&self, p: [f64; 2]) -> bool {
        p[0] >= 0.0
            && p[1] >= 0.0
            && p[0] < f64::from(self.layout.width)
            && p[1] < f64::from(self.layout.height)
    }

    fn on_road(&self, p: [f64; 2], margin: f64) -> bool {
        self.rects.iter().any(|r| within(r, p, margin))
    }

    fn in_block(&self, p: [f64; 2]) -> bool {
        if !self.inside_image(p) {
            return false;
        }
        let (x, y) = (p[0] as u32, p[1] as u32);
        self.layout.blocks.iter().any(|b| b.contains_pixel(x, y))
    }
}

/// Whether `p` lies in `r` grown by `margin`.
fn within(r: &RoadRect, p: [f64; 2], margin: f64) -> bool {
    r.x[0] - margin <= p[0]
        && p[0] <= r.x[1] + margin
        && r.y[0] - margin <= p[1]
        && p[1] <= r.y[1] + margin
}

fn image_point(road: &Road, along: f64, across: f64) -> [f64; 2] {
    match road.axis {
        Axis::Horizontal => [along, across],
        Axis::Vertical => [across, along],
    }
}

/// Direction of the traffic on the `high` (below / right) or low side of a road: keeping
/// right, the side is on the driver's right, so travel = side rotated a quarter turn.
pub fn travel(axis: Axis, high: bool) -> [f64; 2] {
    let side = match (axis, high) {
        (Axis::Horizontal, true) => [0.0, 1.0],
        (Axis::Horizontal, false) => [0.0, -1.0],
        (Axis::Vertical, true) => [1.0, 0.0],
        (Axis::Vertical, false) => [-1.0, 0.0],
    };
    // Heading h has its right-hand side at (-h.z, h.x) (x east, z south), so h = (s.z, -s.x).
    [side[1], -side[0]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn traffic_keeps_right() {
        // (axis, high side) → heading: south lane runs east, east lane runs north, …
        let cases = [
            (Axis::Horizontal, true, [1.0, 0.0]),
            (Axis::Horizontal, false, [-1.0, 0.0]),
            (Axis::Vertical, true, [0.0, -1.0]),
            (Axis::Vertical, false, [0.0, 1.0]),
        ];
        for (axis, high, want) in cases {
            let got = travel(axis, high);
            assert_eq!(got.map(|v: f64| v + 0.0), want, "{axis:?} {high}");
        }
    }
}
