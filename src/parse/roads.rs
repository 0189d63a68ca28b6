//! Roads: class map → the roads, one per group of centre-line runs.

use super::class_map::ClassMap;
use super::run_table::{Run, RunRule, RunTable};
use crate::model::PixelClass;
use crate::model::{Axis, Road};

/// Shortest centre-line run that makes a road: the paper's "longer than 5 pixels".
pub const MIN_LINE_RUN: u32 = 6;
/// Gaps of up to this many px in a noisy centre line do not split the road.
pub const LINE_GAP: u32 = 2;

/// The roads of `map`: horizontal ones first, each group ordered by (line, start), with
/// ids in that order.
///
/// Runs of line pixels along rows (for horizontal roads) or columns (vertical ones) longer
/// than 5 px make up centre lines; runs on neighbouring rows (columns) that overlap along the
/// road are one line smeared by anti-aliasing, so they are grouped into one road. Its line
/// position is the length-weighted mean of the runs' pixel centres, its extent their union.
/// The surface edges are measured across at every position along the line: the run of road
/// or line pixels through the line's pixel, its low and high ends each taken as the median
/// over the road's length. At a crossing that run runs on along the other road; the median
/// ignores it as long as crossings cover less than half of the road.
///
/// Dead ends and T-junctions need no special case: a road ends where its line ends, and a
/// side road's line ends where it meets the main road.
pub fn find_roads(map: &ClassMap) -> Vec<Road> {
    let line = RunRule {
        classes: &[PixelClass::Line],
        bridge: LINE_GAP,
        min_len: MIN_LINE_RUN,
    };
    let surface = RunRule {
        classes: &[PixelClass::Road, PixelClass::Line],
        bridge: 0,
        min_len: 1,
    };
    let mut roads = Vec::new();
    let horizontal = RunTable::rows(map, line).groups();
    if !horizontal.is_empty() {
        let across = RunTable::columns(map, surface);
        roads.extend(
            horizontal
                .iter()
                .map(|g| road(Axis::Horizontal, g, &across)),
        );
    }
    let vertical = RunTable::columns(map, line).groups();
    if !vertical.is_empty() {
        let across = RunTable::rows(map, surface);
        roads.extend(vertical.iter().map(|g| road(Axis::Vertical, g, &across)));
    }
    roads.sort_by(|a, b| {
        (a.axis.cmp(&b.axis))
            .then(a.line.total_cmp(&b.line))
            .then(a.start.total_cmp(&b.start))
    });
    for (id, road) in roads.iter_mut().enumerate() {
        road.id = id as u32;
    }
    roads
}

/// The road whose centre line is the group `runs` of `(across index, along run)`; `surface`
/// holds the road-or-line runs across the road, indexed by the along position.
fn road(axis: Axis, runs: &[(u32, Run)], surface: &RunTable) -> Road {
    let start = runs.iter().map(|(_, r)| r[0]).min().unwrap_or(0);
    let end = runs.iter().map(|(_, r)| r[1]).max().unwrap_or(0);
    let (mut weight, mut moment) = (0.0, 0.0);
    for &(i, [a, b]) in runs {
        let len = f64::from(b - a);
        weight += len;
        moment += len * (f64::from(i) + 0.5);
    }
    let line = if weight > 0.0 { moment / weight } else { 0.0 };

    let through = line.floor() as u32;
    let mut lows = Vec::with_capacity((end - start) as usize);
    let mut highs = Vec::with_capacity((end - start) as usize);
    for pos in start..end {
        if let Some([low, high]) = surface.run_at(pos as usize, through) {
            lows.push(low);
            highs.push(high);
        }
    }
    let edges = match (median(&mut lows), median(&mut highs)) {
        (Some(low), Some(high)) => [low, high],
        _ => [f64::from(through), f64::from(through) + 1.0],
    };
    Road {
        id: 0,
        axis,
        start: f64::from(start),
        end: f64::from(end),
        line,
        edges,
    }
}

/// The median (mean of the middle two for an even count).
fn median(values: &mut [u32]) -> Option<f64> {
    let n = values.len();
    if n == 0 {
        return None;
    }
    values.sort_unstable();
    Some(if n % 2 == 1 {
        f64::from(values[n / 2])
    } else {
        (f64::from(values[n / 2 - 1]) + f64::from(values[n / 2])) / 2.0
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn summary(roads: &[Road]) -> Vec<(Axis, f64, f64, f64, [f64; 2])> {
        roads
            .iter()
            .map(|r| (r.axis, r.start, r.end, r.line, r.edges))
            .collect()
    }

    #[test]
    fn short_runs_are_not_roads_and_small_gaps_do_not_split() {
        let cases: &[(&[&str], usize)] = &[
            (&["yyyyy"], 0),        // 5 px: not longer than 5
            (&["yyyyyy"], 1),       // 6 px
            (&["yyy..yyy"], 1),     // a 2-px gap is bridged
            (&["yyy...yyyyyy"], 1), // a 3-px gap splits; the left part is too short
            (&["yyyyyy...yyyyyy"], 2),
        ];
        for (rows, count) in cases {
            assert_eq!(find_roads(&ClassMap::drawn(rows)).len(), *count, "{rows:?}");
        }
    }

    #[test]
    fn a_line_smeared_over_two_rows_is_one_road() {
        let rows = [
            "..............",
            "rrrrrrrrrrrrrr",
            "yyyyyyyy..rrrr",
            "rrrryyyyyyyyyr",
            "rrrrrrrrrrrrrr",
            "..............",
        ];
        let roads = find_roads(&ClassMap::drawn(&rows));
        assert_eq!(roads.len(), 1);
        let r = &roads[0];
        assert_eq!((r.axis, r.start, r.end), (Axis::Horizontal, 0.0, 13.0));
        // 8 px on row 2, 9 px on row 3.
        assert!((r.line - (8.0 * 2.5 + 9.0 * 3.5) / 17.0).abs() < 1e-12);
        assert_eq!(r.edges, [1.0, 5.0]);
    }

    #[test]
    fn crossings_do_not_widen_a_road() {
        let mut rows = vec!["....rryrr....."; 3];
        rows.extend(["rrrrrryrrrrrrr", "yyyyyyyyyyyyyy", "rrrrrryrrrrrrr"]);
        rows.extend(vec!["....rryrr....."; 4]);
        let roads = find_roads(&ClassMap::drawn(&rows));
        assert_eq!(
            summary(&roads),
            vec![
                (Axis::Horizontal, 0.0, 14.0, 4.5, [3.0, 6.0]),
                (Axis::Vertical, 0.0, 10.0, 6.5, [4.0, 9.0]),
            ]
        );
        assert_eq!(roads.iter().map(|r| r.id).collect::<Vec<_>>(), vec![0, 1]);
    }

    #[test]
    fn median_of_even_and_odd_counts() {
        assert_eq!(median(&mut []), None);
        assert_eq!(median(&mut [5, 1, 3]), Some(3.0));
        assert_eq!(median(&mut [4, 1, 3, 2]), Some(2.5));
    }
}
