//! Footprints (any planar unit) → "does any of them near this one pass a test?", answered
//! from a grid of buckets instead of a scan of every footprint.
//!
//! Placing asks spatial questions of everything placed before: does an object's footprint
//! overlap one taken (lamps, signs, benches, cars, trees)? is a plaza tree clear of every
//! building? is another building between a wall and its road? Asked of every footprint,
//! they are quadratic in the city's size: `specs/mirrored.toml` (48,000 buildings) spent 25
//! of its 30 build seconds finding its walls, and 16 times day.toml's objects 5 seconds
//! placing them. A query tests the footprints whose box meets the probe's box (widened by
//! [`MARGIN`], far more than any rounding), and always those that cannot be bucketed
//! (non-finite or huge); a test that can only fail (for [`FootprintGrid::all_near`]) or
//! pass (for [`FootprintGrid::any_near`]) for two footprints whose boxes meet (an overlap,
//! a distance below the sum of radii, a building between a wall and a road) therefore
//! answers what a scan of every footprint answers.

use std::collections::BTreeMap;

use super::ground_spots::Footprint;
use crate::model::geometry::rounding::floor;

/// Widening of a probe's box, in the footprints' unit, so rounding in a box's edges never
/// drops a candidate.
const MARGIN: f64 = 0.01;
/// Buckets along a side beyond which a box is not bucketed (tested by every query).
const MAX_SPAN: i64 = 1024;

pub(super) struct FootprintGrid {
    /// Side of a bucket, in the footprints' unit.
    cell: f64,
    footprints: Vec<Footprint>,
    /// Footprint indices per bucket (column, row), ascending.
    buckets: BTreeMap<(i64, i64), Vec<u32>>,
    /// Footprints in no bucket, ascending.
    everywhere: Vec<u32>,
}

impl FootprintGrid {
    /// An empty grid of buckets `cell` on a side: about the size of most footprints.
    pub(super) fn new(cell: f64) -> FootprintGrid {
        FootprintGrid {
            cell,
            footprints: Vec::new(),
            buckets: BTreeMap::new(),
            everywhere: Vec::new(),
        }
    }

    pub(super) fn push(&mut self, footprint: Footprint) {
        let index = self.footprints.len() as u32;
        match self.span(bounds(&footprint)) {
            Some((lo, hi)) => {
                for row in lo[1]..=hi[1] {
                    for column in lo[0]..=hi[0] {
                        self.buckets.entry((column, row)).or_default().push(index);
                    }
                }
            }
            None => self.everywhere.push(index),
        }
        self.footprints.push(footprint);
    }

    /// Every footprint, in the order pushed.
    pub(super) fn footprints(&self) -> &[Footprint] {
        &self.footprints
    }

    pub(super) fn last(&self) -> Option<&Footprint> {
        self.footprints.last()
    }

    /// Removes the footprint pushed last.
    pub(super) fn pop(&mut self) {
        let Some(footprint) = self.footprints.pop() else {
            return;
        };
        match self.span(bounds(&footprint)) {
            Some((lo, hi)) => {
                for row in lo[1]..=hi[1] {
                    for column in lo[0]..=hi[0] {
                        if let Some(bucket) = self.buckets.get_mut(&(column, row)) {
                            bucket.pop();
                        }
                    }
                }
            }
            None => {
                self.everywhere.pop();
            }
        }
    }

    /// Whether `hit` holds for a footprint (its index in push order, and itself) whose box
    /// meets `probe`'s box, or that is in no bucket. A footprint may be tested more than
    /// once.
    pub(super) fn any_near(
        &self,
        probe: &Footprint,
        mut hit: impl FnMut(usize, &Footprint) -> bool,
    ) -> bool {
        let b = bounds(probe);
        let widened = [b[0] - MARGIN, b[1] - MARGIN, b[2] + MARGIN, b[3] + MARGIN];
        let Some((lo, hi)) = self.span(widened) else {
            return self.footprints.iter().enumerate().any(|(i, f)| hit(i, f));
        };
        let mut test = |i: &u32| hit(*i as usize, &self.footprints[*i as usize]);
        for row in lo[1]..=hi[1] {
            for column in lo[0]..=hi[0] {
                if let Some(bucket) = self.buckets.get(&(column, row))
                    && bucket.iter().any(&mut test)
                {
                    return true;
                }
            }
        }
        self.everywhere.iter().any(test)
    }

    /// Whether `ok` holds for every footprint whose box meets `probe`'s box (or that is in
    /// no bucket): for a test that holds wherever two boxes are apart (a distance of at
    /// least the sum of radii), whether it holds for every footprint.
    pub(super) fn all_near(
        &self,
        probe: &Footprint,
        mut ok: impl FnMut(&Footprint) -> bool,
    ) -> bool {
        !self.any_near(probe, |_, f| !ok(f))
    }

    /// Whether `probe` overlaps a footprint of the grid ([`Footprint::overlaps`]).
    pub(super) fn overlaps(&self, probe: &Footprint) -> bool {
        self.any_near(probe, |_, taken| taken.overlaps(probe))
    }

    /// The first and last bucket a box reaches, or None for a box that is not finite, is
    /// inverted or spans more than [`MAX_SPAN`] buckets a side.
    fn span(&self, b: [f64; 4]) -> Option<([i64; 2], [i64; 2])> {
        if !b.iter().all(|v| v.is_finite()) {
            return None;
        }
        let cell = |v: f64| floor(v / self.cell) as i64;
        let (lo, hi) = ([cell(b[0]), cell(b[1])], [cell(b[2]), cell(b[3])]);
        let fits = |k: usize| (0..=MAX_SPAN).contains(&(hi[k] - lo[k]));
        (fits(0) && fits(1)).then_some((lo, hi))
    }
}

/// `[x0, z0, x1, z1]` of a footprint.
fn bounds(footprint: &Footprint) -> [f64; 4] {
    match *footprint {
        Footprint::Circle(c, r) => [c[0] - r, c[1] - r, c[0] + r, c[1] + r],
        Footprint::Rect(x, z) => [x[0], z[0], x[1], z[1]],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::RngExt;

    /// Against a scan of every footprint: circles and rectangles scattered over a city,
    /// some huge, one not finite, with pops between the pushes.
    #[test]
    fn overlaps_answers_what_a_scan_answers() {
        let mut rng = crate::rng::stream(99, "footprint grid test", 0);
        let mut next = |n: f64| rng.random::<f64>() * n;
        let mut shape = |big: bool| {
            let (x, z) = (next(400.0) - 20.0, next(400.0) - 20.0);
            let size = if big { 20_000.0 } else { 6.0 };
            if next(1.0) < 0.5 {
                Footprint::Circle([x, z], next(size))
            } else {
                Footprint::Rect([x, x + next(size)], [z, z + next(size)])
            }
        };
        let mut grid = FootprintGrid::new(8.0);
        let mut all: Vec<Footprint> = Vec::new();
        grid.push(Footprint::Circle([f64::NAN, 1.0], 2.0));
        all.push(Footprint::Circle([f64::NAN, 1.0], 2.0));
        let (mut hits, mut misses) = (0, 0);
        for i in 0..3000 {
            let probe = shape(i % 500 == 7);
            let scan = all.iter().any(|t| t.overlaps(&probe));
            assert_eq!(grid.overlaps(&probe), scan, "probe {i}: {probe:?}");
            if scan {
                hits += 1;
            } else {
                misses += 1;
                grid.push(probe);
                all.push(probe);
            }
            if i % 7 == 0 {
                grid.pop();
                all.pop();
            }
            // By their printing: the NaN circle equals nothing, not even itself.
            assert_eq!(format!("{:?}", grid.last()), format!("{:?}", all.last()));
        }
        assert!(hits > 300 && misses > 300, "{hits} hits, {misses} misses");
    }

    /// `any_near` hands a test each candidate's push index: on a scatter of rectangles, the
    /// rectangles a query's test finds are those a scan finds (the building test of
    /// `wall_text::facing_walls`).
    #[test]
    fn any_near_finds_by_index_what_a_scan_finds() {
        let mut rng = crate::rng::stream(12345, "footprint grid test", 1);
        let mut next = |n: u32| f64::from(rng.random_range(0..n));
        let mut grid = FootprintGrid::new(32.0);
        let mut boxes = Vec::new();
        for _ in 0..400 {
            let (x, y) = (next(700), next(700));
            let b = Footprint::Rect([x, x + next(60)], [y, y + next(60)]);
            grid.push(b);
            boxes.push(b);
        }
        for q in 0..400 {
            let (x, y) = (next(900) - 100.0, next(900) - 100.0);
            let probe = Footprint::Rect([x, x + next(80)], [y, y + next(80)]);
            let skip = q % boxes.len();
            let test = |i: usize, f: &Footprint| i != skip && f.overlaps(&probe);
            let scan = boxes.iter().enumerate().any(|(i, f)| test(i, f));
            assert_eq!(grid.any_near(&probe, test), scan, "query {q}: {probe:?}");
        }
    }
}
