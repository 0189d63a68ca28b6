//! The one painter of road markings, for layouts and maps: a road's [`Path`] and what is
//! painted along it ([`RoadMarks`]) → its marking mesh. Each input only says where the
//! marks go: `markings` for a layout's roads (lanes by [`StreetProfile`], a zebra on each
//! approach to a crossing), `map_markings` for a map's (lanes by width, the map's
//! crossings, signals, stop and give-way nodes). Everything is measured along the path:
//! arc length from its first point (`along`), and metres right of it (`across`, right as
//! seen travelling along it: for a road running east, south).
//!
//! - **Lines.** Each segment of the path lists its lines (offset across, dashed or solid);
//!   they are painted [`LINE_WIDTH`] wide over the road's stretches: a dashed line as
//!   the whole [`DASH`]es that fit in a stretch, [`GAP`] apart and centred in it (counted
//!   along the path, so they run on through a bend), a solid line over the whole stretch.
//! - **Zebras.** Bars [`BAR`] wide and [`BAR_GAP`] apart over the zebra's `along`,
//!   centred across its `across` (kerb to kerb less [`CURB_CLEARANCE`]).
//! - **Stop lines.** A bar over `along` and `across`; a give-way line is a row of
//!   triangles ([`TOOTH_BASE`] wide, [`TOOTH_GAP`] apart, centred across) whose apexes
//!   point at the traffic it stops.
//!
//! [`StreetProfile`]: crate::model::geometry::StreetProfile

use crate::model::geometry::polygon::{direction, distance};
use crate::model::geometry::zebras::{DASH, LINE_WIDTH};
use crate::model::geometry::{MARKING_Y, MeshBuilder, UP};

/// Gap between dashes, in metres (their length and the lines' width: [`DASH`],
/// [`LINE_WIDTH`]).
pub const GAP: f64 = 6.0;
/// A zebra crossing's bars' width and the gap between them, and the road kept clear at
/// each kerb, in metres (its length:
/// [`ZEBRA_DEPTH`](crate::model::geometry::zebras::ZEBRA_DEPTH)).
pub const BAR: f64 = 0.5;
pub const BAR_GAP: f64 = 0.6;
pub const CURB_CLEARANCE: f64 = 0.3;
/// Width of a stop line along the road, in metres.
pub const STOP_LINE: f64 = 0.4;
/// A give-way line's triangles: their length along the road, metres (the Vienna
/// Convention's 0.60–0.70 m, Annex 2 §33).
pub const TOOTH_LENGTH: f64 = 0.6;
/// A give-way triangle's base across the road, metres (0.40–0.60 m, the same).
pub const TOOTH_BASE: f64 = 0.5;
/// The gap between two give-way triangles' bases, metres.
pub const TOOTH_GAP: f64 = 0.25;

/// A road's centreline as its markings are painted along it.
pub struct Path {
    points: Vec<[f64; 2]>,
    /// Arc length at each point, metres from the first.
    at: Vec<f64>,
}

impl Path {
    /// The path through `points` (world x, z; at least two).
    pub fn new(points: Vec<[f64; 2]>) -> Path {
        let mut at = vec![0.0];
        for w in points.windows(2) {
            at.push(at[at.len() - 1] + distance(w[0], w[1]));
        }
        Path { points, at }
    }

    /// The segments' count.
    pub fn segments(&self) -> usize {
        self.points.len().saturating_sub(1)
    }

    /// The world point of segment `s` at `l` metres along it from its first point and `c`
    /// metres right of it; None for a segment of no length.
    fn on_segment(&self, s: usize) -> Option<impl Fn(f64, f64) -> [f64; 3]> {
        let (a, b) = (*self.points.get(s)?, *self.points.get(s + 1)?);
        let t = direction(a, b)?;
        // Right of a → b (x east, z south).
        let n = [-t[1], t[0]];
        Some(move |l: f64, c: f64| {
            [
                a[0] + t[0] * l + n[0] * c,
                MARKING_Y,
                a[1] + t[1] * l + n[1] * c,
            ]
        })
    }
}

/// One line along a road: metres right of the centreline, and whether it is solid (else
/// dashed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line {
    pub offset: f64,
    pub solid: bool,
}

/// A zebra crossing: on which segment, over which arc lengths, and the range its bars are
/// centred in (metres right of the centreline).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZebraMark {
    pub segment: usize,
    pub along: [f64; 2],
    pub across: [f64; 2],
}

/// A stop or give-way line: on which segment, over which arc lengths, across which
/// offsets; `give_way`: triangles pointing at the traffic running this way (1: along the
/// path, −1: against it), else a bar.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StopMark {
    pub segment: usize,
    pub along: [f64; 2],
    pub across: [f64; 2],
    pub give_way: Option<f64>,
}

/// Everything painted on one road, along its [`Path`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RoadMarks {
    /// Per segment of the path, its lines (none on an unpaved one).
    pub lines: Vec<Vec<Line>>,
    /// The arc-length ranges the lines run over, in order.
    pub stretches: Vec<[f64; 2]>,
    pub zebras: Vec<ZebraMark>,
    pub stops: Vec<StopMark>,
}

/// Paints `marks` along `path` into `mesh`: the zebras, the stop lines, then per stretch
/// its dashes and its solid lines.
pub fn paint(mesh: &mut MeshBuilder, path: &Path, marks: &RoadMarks) {
    // A mark on a segment the path does not have is left out.
    let from_start = |s: usize, along: [f64; 2]| path.at.get(s).map(|&at| along.map(|a| a - at));
    for zebra in &marks.zebras {
        let Some(along) = from_start(zebra.segment, zebra.along) else {
            continue;
        };
        for bar in centred_pieces(zebra.across, BAR, BAR_GAP) {
            rect(mesh, path, zebra.segment, along, bar);
        }
    }
    for stop in &marks.stops {
        let Some(along) = from_start(stop.segment, stop.along) else {
            continue;
        };
        match stop.give_way {
            Some(sign) => teeth(mesh, path, stop.segment, along, stop.across, sign),
            None => rect(mesh, path, stop.segment, along, stop.across),
        }
    }
    for &stretch in &marks.stretches {
        for dash in centred_pieces(stretch, DASH, GAP) {
            lines(mesh, path, marks, dash, false);
        }
        lines(mesh, path, marks, stretch, true);
    }
}

/// The `solid` (or dashed) lines of `marks` over arc lengths `along`, on every segment
/// they cross.
fn lines(mesh: &mut MeshBuilder, path: &Path, marks: &RoadMarks, along: [f64; 2], solid: bool) {
    let half = LINE_WIDTH / 2.0;
    for (s, lines) in marks.lines.iter().enumerate().take(path.segments()) {
        let (a, b) = (path.at[s].max(along[0]), path.at[s + 1].min(along[1]));
        if a >= b {
            continue;
        }
        for line in lines.iter().filter(|l| l.solid == solid) {
            rect(
                mesh,
                path,
                s,
                [a - path.at[s], b - path.at[s]],
                [line.offset - half, line.offset + half],
            );
        }
    }
}

/// A marking quad on segment `s`: `along` it (metres from its first point) and `across` it
/// (metres right of it).
fn rect(mesh: &mut MeshBuilder, path: &Path, s: usize, along: [f64; 2], across: [f64; 2]) {
    let Some(at) = path.on_segment(s) else {
        return;
    };
    let corners = [
        at(along[0], across[0]),
        at(along[1], across[0]),
        at(along[1], across[1]),
        at(along[0], across[1]),
    ];
    // The whole mark is one white quad; uv 0..1 over it.
    let uvs = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    mesh.quad(corners, UP, uvs);
}

/// A give-way line's triangles over `along` (from segment `s`'s start) and `across`, for
/// traffic running `sign`: bases on the side it drives to, apexes towards it.
fn teeth(
    mesh: &mut MeshBuilder,
    path: &Path,
    s: usize,
    along: [f64; 2],
    across: [f64; 2],
    sign: f64,
) {
    let Some(at) = path.on_segment(s) else {
        return;
    };
    let (base, apex) = if sign > 0.0 {
        (along[1], along[0])
    } else {
        (along[0], along[1])
    };
    for tooth in centred_pieces(across, TOOTH_BASE, TOOTH_GAP) {
        let corners = [
            at(base, tooth[0]),
            at(base, tooth[1]),
            at(apex, tooth[0] + TOOTH_BASE / 2.0),
        ];
        mesh.triangle(corners, UP, [[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]]);
    }
}

/// As many pieces `length` long and `gap` apart as fit in `range`, centred in it.
pub fn centred_pieces(range: [f64; 2], length: f64, gap: f64) -> Vec<[f64; 2]> {
    let room = range[1] - range[0];
    let period = length + gap;
    // n pieces take n·length + (n − 1)·gap.
    let n = ((room + gap) / period).floor();
    // A non-finite range or fewer than one piece: nothing.
    if !n.is_finite() || n < 1.0 {
        return Vec::new();
    }
    let first = range[0] + (room - (n * period - gap)) / 2.0;
    (0..n as u64)
        .map(|k| {
            let a = first + k as f64 * period;
            [a, a + length]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Mesh;

    #[test]
    fn pieces_are_centred_and_stay_inside() {
        let dashes = |r| centred_pieces(r, DASH, GAP);
        assert_eq!(dashes([0.0, 2.9]), Vec::<[f64; 2]>::new());
        assert_eq!(dashes([10.0, 14.0]), vec![[10.5, 13.5]]);
        // 20 m: two dashes (3 + 6 + 3 = 12) with 4 m either side.
        assert_eq!(dashes([0.0, 20.0]), vec![[4.0, 7.0], [13.0, 16.0]]);
        assert_eq!(dashes([0.0, 21.0]).len(), 3);
        let many = dashes([3.0, 700.0]);
        assert_eq!(many.len(), 78);
        assert!(many[0][0] >= 3.0 && many[77][1] <= 700.0);
        assert!(centred_pieces([0.0, f64::NAN], 1.0, 1.0).is_empty());
    }

    /// The plan corners (x, z) of each quad of `mesh` (its first whole fours), as painted.
    fn faces(mesh: &Mesh, corners: usize) -> Vec<Vec<[f64; 2]>> {
        mesh.positions
            .chunks_exact(corners)
            .map(|c| {
                c.iter()
                    .map(|p| [f64::from(p[0]), f64::from(p[2])])
                    .collect()
            })
            .collect()
    }

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).abs() < 1e-5 && (a[1] - b[1]).abs() < 1e-5
    }

    #[test]
    fn lines_run_on_through_a_bend_and_solid_lines_fill_their_stretch() {
        // East 10 m, then south 10 m: right of the path is south, then west.
        let path = Path::new(vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]);
        let line = |offset, solid| Line { offset, solid };
        let marks = RoadMarks {
            lines: vec![
                vec![line(0.0, false), line(2.0, true)],
                vec![line(0.0, false)],
            ],
            stretches: vec![[0.0, 12.0]],
            ..RoadMarks::default()
        };
        let mut mesh = MeshBuilder::new(0);
        paint(&mut mesh, &path, &marks);
        let mesh = mesh.finish();
        let quads = faces(&mesh, 4);
        // Two dashes fill 12 m: [0, 3] and [9, 12], the second across the bend (two quads);
        // then the solid line, on the first segment only.
        assert_eq!(quads.len(), 4, "{quads:?}");
        let h = LINE_WIDTH / 2.0;
        let has = |q: &[[f64; 2]], p: [f64; 2]| q.iter().any(|&c| close(c, p));
        assert!(has(&quads[0], [0.0, -h]) && has(&quads[0], [3.0, h]));
        assert!(has(&quads[1], [9.0, -h]) && has(&quads[1], [10.0, h]));
        // Past the bend the dash runs south, 2 m past the corner; right of it is west.
        assert!(has(&quads[2], [10.0 + h, 0.0]) && has(&quads[2], [10.0 - h, 2.0]));
        assert!(has(&quads[3], [0.0, 2.0 - h]) && has(&quads[3], [10.0, 2.0 + h]));
    }

    #[test]
    fn marks_off_the_path_are_left_out() {
        let marks = RoadMarks {
            lines: vec![vec![Line {
                offset: 0.0,
                solid: true,
            }]],
            stretches: vec![[0.0, 5.0]],
            zebras: vec![ZebraMark {
                segment: 3,
                along: [1.0, 4.0],
                across: [-2.0, 2.0],
            }],
            stops: vec![StopMark {
                segment: 1,
                along: [1.0, 1.4],
                across: [0.0, 2.0],
                give_way: Some(1.0),
            }],
        };
        for points in [vec![], vec![[0.0, 0.0]], vec![[0.0, 0.0], [0.0, 0.0]]] {
            let mut mesh = MeshBuilder::new(0);
            paint(&mut mesh, &Path::new(points), &marks);
            assert!(mesh.is_empty());
        }
        // On a real segment the line is painted, the marks off it are not.
        let mut mesh = MeshBuilder::new(0);
        paint(&mut mesh, &Path::new(vec![[0.0, 0.0], [5.0, 0.0]]), &marks);
        assert_eq!(mesh.finish().positions.len(), 4);
    }

    #[test]
    fn zebras_stops_and_teeth_sit_where_their_marks_say() {
        let path = Path::new(vec![[0.0, 0.0], [0.0, 20.0]]);
        let marks = RoadMarks {
            lines: vec![Vec::new()],
            zebras: vec![ZebraMark {
                segment: 0,
                along: [5.0, 8.0],
                across: [-1.0, 1.0],
            }],
            stops: vec![
                StopMark {
                    segment: 0,
                    along: [2.0, 2.4],
                    across: [0.1, 1.0],
                    give_way: None,
                },
                StopMark {
                    segment: 0,
                    along: [10.0, 10.6],
                    across: [-1.0, 0.0],
                    give_way: Some(-1.0),
                },
            ],
            ..RoadMarks::default()
        };
        let mut mesh = MeshBuilder::new(0);
        paint(&mut mesh, &path, &marks);
        let mesh = mesh.finish();
        // 2 m holds two bars (0.5 + 0.6 + 0.5 = 1.6); with the stop line, 3 quads (12
        // corners); 1 m holds one tooth (3 corners).
        assert_eq!(mesh.positions.len(), 15);
        let quads = faces(&mesh, 4);
        // Running south, right is west (−x): a bar at across [−0.8, −0.3] lies at
        // x ∈ [0.3, 0.8].
        let has = |q: &[[f64; 2]], p: [f64; 2]| q.iter().any(|&c| close(c, p));
        assert!(has(&quads[0], [0.8, 5.0]) && has(&quads[0], [0.3, 8.0]));
        assert!(has(&quads[1], [-0.3, 5.0]) && has(&quads[1], [-0.8, 8.0]));
        assert!(has(&quads[2], [-0.1, 2.0]) && has(&quads[2], [-1.0, 2.4]));
        // The tooth stops traffic running north (against the path): its base on the far
        // side (10), its apex at 10.6, towards that traffic, centred across [0, 1] m east.
        let tooth: Vec<[f64; 2]> = mesh.positions[12..]
            .iter()
            .map(|p| [f64::from(p[0]), f64::from(p[2])])
            .collect();
        assert!(tooth.iter().any(|&c| close(c, [0.5, 10.6])), "{tooth:?}");
        assert!(tooth.iter().any(|&c| close(c, [0.75, 10.0])), "{tooth:?}");
        assert!(tooth.iter().any(|&c| close(c, [0.25, 10.0])), "{tooth:?}");
    }
}
