//! The ways people walk, kept clear on the ground: a person crossing a road takes the
//! whole way over its zebra to its place on the far side (the half of the zebra on its
//! right, so people crossing either way never meet), and a person walking along a strip
//! walks as far as nothing taken stands in its way.

use rand::RngExt;
use rand_pcg::Pcg64;

use super::{Footprint, GroundSpots, Spot, image_point, travel};
use crate::model::{Axis, Crossing, Road};

/// The farthest a person walks along a strip, metres (two minutes at a brisk walk).
pub const MAX_WALK: f64 = 200.0;

/// A spot on or at a zebra crossing with the way its person crosses by.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrossingSpot {
    /// Where it stands; `travel` is the way it crosses.
    pub spot: Spot,
    pub crossing: Crossing,
    /// How far it walks to its place on the far side, metres.
    pub reach: f64,
}

impl<'a> GroundSpots<'a> {
    /// A free spot on a zebra crossing (uniform among them) for a person of `radius`
    /// metres crossing it: in the half of the zebra on its right, at most `reach` metres
    /// either side of the road's centre line and `radius` inside the curbs, crossing
    /// either way to `beyond` metres past the far curb. The whole way there is taken. None
    /// when the city has no zebra crossing, or after `attempts`.
    pub fn zebra(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        reach: f64,
        beyond: f64,
        attempts: u32,
    ) -> Option<CrossingSpot> {
        (0..attempts).find_map(|_| {
            let (road, zebra) = self.pick_zebra(rng)?;
            let half = (road.edges[1] - road.edges[0]) * self.mpp / 2.0;
            let limit = reach.min(half - radius);
            let across = road.line * self.mpp + (2.0 * rng.random::<f64>() - 1.0) * limit;
            let sign = if rng.random::<bool>() { -1.0 } else { 1.0 };
            let along = keep_right(road.axis, zebra, sign, radius, rng.random())?;
            if !(limit >= 0.0 && across.is_finite()) {
                return None;
            }
            let far = self.curb(road, sign) + sign * beyond;
            self.crossing_way(road, along, [across, far], radius)?;
            Some(CrossingSpot {
                spot: Spot {
                    position: image_point(road, along, across),
                    travel: self.across(road, sign),
                    road: road.id,
                },
                crossing: Crossing {
                    zebra,
                    waiting: false,
                },
                reach: (far - across).abs(),
            })
        })
    }

    /// A free spot in the sidewalk strip at one end of a zebra crossing, `from_curb` metres
    /// from the curb, for a person of `radius` metres waiting to cross: in the half of the
    /// zebra on its right as it crosses, its `travel` across the curb at the road. Its way
    /// over to the same distance past the far curb is taken. None after `attempts`.
    pub fn zebra_kerb(
        &mut self,
        rng: &mut Pcg64,
        radius: f64,
        from_curb: f64,
        attempts: u32,
    ) -> Option<CrossingSpot> {
        (0..attempts).find_map(|_| {
            let (road, zebra) = self.pick_zebra(rng)?;
            let high: bool = rng.random();
            // It crosses towards the other side.
            let sign = if high { -1.0 } else { 1.0 };
            let along = keep_right(road.axis, zebra, sign, radius, rng.random())?;
            let start = self.curb(road, -sign) - sign * from_curb;
            let far = self.curb(road, sign) + sign * from_curb;
            // Its own end must be a strip too, as the far one is.
            self.sidewalk(road, along, start, from_curb)?;
            self.crossing_way(road, along, [start, far], radius)?;
            Some(CrossingSpot {
                spot: Spot {
                    position: image_point(road, along, start),
                    travel: self.across(road, sign),
                    road: road.id,
                },
                crossing: Crossing {
                    zebra,
                    waiting: true,
                },
                reach: (far - start).abs(),
            })
        })
    }

    /// How far a person of `radius` metres at `from` (metres) walking along `dir` (a
    /// unit vector along a road's axis) beside road `road` gets before it touches
    /// something taken (but people walking along strips: [`GroundSpots::mark_walker`]),
    /// another road, a block or the image's edge; at most [`MAX_WALK`].
    pub fn free_run(&self, from: [f64; 2], dir: [f64; 2], radius: f64, road: u32) -> f64 {
        let side = [-dir[1], dir[0]];
        let (s0, c0) = (dot(from, dir), dot(from, side));
        let mut run = MAX_WALK;
        for (i, f) in self.taken.footprints().iter().enumerate() {
            if self.walkers.binary_search(&i).is_ok() {
                continue;
            }
            let hit = match *f {
                Footprint::Circle(p, r) => {
                    let gap = (dot(p, side) - c0).abs();
                    let reach = radius + r;
                    (gap < reach).then(|| dot(p, dir) - s0 - (reach * reach - gap * gap).sqrt())
                }
                Footprint::Rect(x, z) => {
                    rect_hit([x, z], dir, side, s0, c0, radius).map(|h| h.max(0.0))
                }
            };
            if let Some(h) = hit.filter(|&h| h > -1e-9) {
                run = run.min(h);
            }
        }
        // Other roads with their strips: a person walks to the corner of its block and
        // no further, so people walking beside crossing roads never meet at a corner.
        let (mpp, strip) = (self.mpp, self.strip_px * self.mpp);
        for (i, r) in self.rects.iter().enumerate() {
            if i == road as usize {
                continue;
            }
            let grown = [
                [r.x[0] * mpp - strip, r.x[1] * mpp + strip],
                [r.y[0] * mpp - strip, r.y[1] * mpp + strip],
            ];
            if let Some(h) = rect_hit(grown, dir, side, s0, c0, radius) {
                run = run.min(h.max(0.0));
            }
        }
        self.block_run(from, dir, radius, run)
    }

    /// How far, up to `run` metres, a circle of `radius` at `from` walking along `dir`
    /// gets before its front or a side meets a block or leaves the image, half a pixel at
    /// a time.
    fn block_run(&self, from: [f64; 2], dir: [f64; 2], radius: f64, run: f64) -> f64 {
        let mpp = self.mpp;
        let side = [-dir[1], dir[0]];
        let point = |s: f64, k: f64| {
            let lead = if k == 0.0 { radius } else { 0.0 };
            [
                (from[0] + dir[0] * (s + lead) + side[0] * k * radius) / mpp,
                (from[1] + dir[1] * (s + lead) + side[1] * k * radius) / mpp,
            ]
        };
        // Only the blocks whose box meets the sweep's.
        let (a, b) = (point(0.0, 1.0), point(run, -1.0));
        let (c, d) = (point(0.0, -1.0), point(run, 1.0));
        let lo = [a, b, c, d]
            .iter()
            .fold([f64::INFINITY; 2], |m, p| [m[0].min(p[0]), m[1].min(p[1])]);
        let hi = [a, b, c, d].iter().fold([f64::NEG_INFINITY; 2], |m, p| {
            [m[0].max(p[0]), m[1].max(p[1])]
        });
        let near: Vec<&crate::model::Block> = self
            .layout
            .blocks
            .iter()
            .filter(|b| {
                f64::from(b.bbox.x0) <= hi[0] + 1.0
                    && lo[0] - 1.0 <= f64::from(b.bbox.x1)
                    && f64::from(b.bbox.y0) <= hi[1] + 1.0
                    && lo[1] - 1.0 <= f64::from(b.bbox.y1)
            })
            .collect();
        let blocked = |p: [f64; 2]| {
            !self.inside_image(p)
                || near
                    .iter()
                    .any(|b| b.contains_pixel(p[0] as u32, p[1] as u32))
        };
        let step = mpp / 2.0;
        let mut s = 0.0;
        while s < run {
            if [0.0, 1.0, -1.0].iter().any(|&k| blocked(point(s, k))) {
                return (s - step).max(0.0);
            }
            s += step;
        }
        run.max(0.0)
    }

    /// A zebra crossing (uniform among them), its road and its range along the road,
    /// metres. None, drawing nothing, when the city has no zebra crossing.
    fn pick_zebra(&self, rng: &mut Pcg64) -> Option<(&'a Road, [f64; 2])> {
        if self.zebras.is_empty() {
            return None;
        }
        let (i, range) = self.zebras[rng.random_range(0..self.zebras.len())];
        Some((&self.layout.roads[i], range))
    }

    /// The across-axis position of `road`'s curb on the side `sign` points to, metres.
    fn curb(&self, road: &Road, sign: f64) -> f64 {
        let edge = if sign > 0.0 {
            road.edges[1]
        } else {
            road.edges[0]
        };
        edge * self.mpp
    }

    /// The unit vector (x, z) across `road` towards the side `sign` points to.
    fn across(&self, road: &Road, sign: f64) -> [f64; 2] {
        // The high side's lanes run along `t`; across is `t` turned a quarter.
        let t = travel(road.axis, true);
        [-t[1] * sign, t[0] * sign]
    }

    /// Whether the point `across` metres across `road` at `along` lies in a strip,
    /// `from_curb` metres from its curb: off every road, inside the image, with no road one
    /// pixel past the strip's far edge (a block, or the crossing road's strip at a corner).
    fn sidewalk(&self, road: &Road, along: f64, across: f64, from_curb: f64) -> Option<()> {
        let px = image_point(road, along / self.mpp, across / self.mpp);
        let out = if across > road.line * self.mpp {
            1.0
        } else {
            -1.0
        };
        let beyond = self.strip_px - from_curb / self.mpp + 1.0;
        let behind = image_point(road, along / self.mpp, across / self.mpp + out * beyond);
        (self.inside_image(px) && !self.on_road(px, 0.0) && !self.on_road(behind, 0.0))
            .then_some(())
    }

    /// Takes the way of a person of `radius` metres crossing `road` at `along` from
    /// `across[0]` to `across[1]` (metres), if its end lies in a strip and nothing taken
    /// is in the way.
    fn crossing_way(
        &mut self,
        road: &Road,
        along: f64,
        across: [f64; 2],
        radius: f64,
    ) -> Option<()> {
        let from_curb = (across[1] - self.curb(road, (across[1] - across[0]).signum())).abs();
        self.sidewalk(road, along, across[1], from_curb)?;
        let (lo, hi) = (across[0].min(across[1]), across[0].max(across[1]));
        let (x, z) = match road.axis {
            Axis::Horizontal => ([along - radius, along + radius], [lo - radius, hi + radius]),
            Axis::Vertical => ([lo - radius, hi + radius], [along - radius, along + radius]),
        };
        self.claim(Footprint::Rect(x, z)).then_some(())
    }
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// Where along a zebra (`zebra`, metres along `axis`) a person of `radius` crossing
/// towards the side `sign` points to walks: in the half on its right, at `u` (0 to 1) of
/// the room there. None when the half is too narrow.
fn keep_right(axis: Axis, zebra: [f64; 2], sign: f64, radius: f64, u: f64) -> Option<f64> {
    // Crossing towards +across, a person's right is −along on a horizontal road (walking
    // south, west is on the right) and +along on a vertical one (walking east, south).
    let right_is_high = match axis {
        Axis::Horizontal => sign < 0.0,
        Axis::Vertical => sign > 0.0,
    };
    let mid = (zebra[0] + zebra[1]) / 2.0;
    let [lo, hi] = if right_is_high {
        [mid, zebra[1]]
    } else {
        [zebra[0], mid]
    };
    let room = hi - lo - 2.0 * radius;
    (room >= 0.0 && u.is_finite()).then_some(lo + radius + u * room)
}

/// Where along `dir` from `s0` a circle of `radius` at `c0` across (on `side`) first
/// touches the rectangle `[x, z]`, if it is in the way: overlapping its band, its near
/// edge ahead of the circle's centre (one the circle stands in, or walks out of, is not).
/// Negative when the circle already reaches into it.
fn rect_hit(
    [x, z]: [[f64; 2]; 2],
    dir: [f64; 2],
    side: [f64; 2],
    s0: f64,
    c0: f64,
    radius: f64,
) -> Option<f64> {
    let corners = [[x[0], z[0]], [x[1], z[0]], [x[0], z[1]], [x[1], z[1]]];
    let span = |u: [f64; 2]| {
        corners
            .iter()
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[a, b], &p| {
                let v = dot(p, u);
                [a.min(v), b.max(v)]
            })
    };
    let (along, across) = (span(dir), span(side));
    // The circle's band overlaps the rectangle's (the circle taken as its square: it
    // stops a little early at a corner, never late).
    (across[0] < c0 + radius && c0 - radius < across[1] && along[0] >= s0)
        .then(|| along[0] - s0 - radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn people_keep_to_the_half_on_their_right() {
        let z = [10.0, 13.0];
        // Horizontal road: crossing south (+z), the right is west (low x).
        assert!(keep_right(Axis::Horizontal, z, 1.0, 0.6, 1.0).unwrap() <= 11.5 - 0.6 + 1e-9);
        assert!(keep_right(Axis::Horizontal, z, -1.0, 0.6, 0.0).unwrap() >= 11.5 + 0.6 - 1e-9);
        // Vertical road: crossing east (+x), the right is south (high z).
        assert!(keep_right(Axis::Vertical, z, 1.0, 0.6, 0.0).unwrap() >= 11.5 + 0.6 - 1e-9);
        assert!(keep_right(Axis::Vertical, z, -1.0, 0.6, 1.0).unwrap() <= 11.5 - 0.6 + 1e-9);
        // Too narrow a half for the person.
        assert_eq!(keep_right(Axis::Vertical, z, 1.0, 0.8, 0.5), None);
    }

    #[test]
    fn a_rectangle_is_in_the_way_only_across_its_band() {
        let r = [[10.0, 12.0], [-1.0, 1.0]];
        // Walking east along z = 0.5 from x = 0: touches at x = 10 − 0.6.
        let hit = rect_hit(r, [1.0, 0.0], [0.0, 1.0], 0.0, 0.5, 0.6).unwrap();
        assert!((hit - 9.4).abs() < 1e-12);
        // Beside it (band clear), behind it, and walking away: not in the way.
        assert_eq!(rect_hit(r, [1.0, 0.0], [0.0, 1.0], 0.0, 1.7, 0.6), None);
        assert_eq!(rect_hit(r, [1.0, 0.0], [0.0, 1.0], 13.0, 0.0, 0.6), None);
        assert_eq!(rect_hit(r, [-1.0, 0.0], [0.0, -1.0], 0.0, 0.0, 0.6), None);
    }
}
