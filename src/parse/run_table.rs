//! RunTable: class map + a set of classes → the runs of those classes along every row (or
//! every column), and the groups of runs that touch across neighbouring lines.

use rayon::prelude::*;

use super::class_map::ClassMap;
use crate::model::PixelClass;

/// A half-open run `[start, end)` along a row or column.
pub type Run = [u32; 2];

/// How runs are cut out of a line of pixels.
#[derive(Clone, Copy, Debug)]
pub struct RunRule<'a> {
    /// The classes a run is made of.
    pub classes: &'a [PixelClass],
    /// Gaps of at most this many other pixels do not break a run.
    pub bridge: u32,
    /// Shortest run kept (its extent, gaps included).
    pub min_len: u32,
}

/// Columns handled by one task when scanning columns: wide enough to read rows in cache
/// lines, narrow enough to spread over threads.
const COLUMN_STRIPE: usize = 64;
/// Rows handled by one task when scanning rows.
const ROW_BAND: u32 = 32;

/// The runs of each line (row `i` or column `i`), sorted along the line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunTable {
    lines: Vec<Vec<Run>>,
}

impl RunTable {
    /// Runs along each row. Bands of rows run in parallel into their own slots; a row equal
    /// to the one above (most rows of a drawn layout) reuses its runs.
    pub fn rows(map: &ClassMap, rule: RunRule) -> RunTable {
        let accept = accepted(rule.classes);
        let height = map.height();
        let bands: Vec<Vec<Vec<Run>>> = (0..height.div_ceil(ROW_BAND))
            .into_par_iter()
            .map(|band| {
                let (y0, y1) = (band * ROW_BAND, ((band + 1) * ROW_BAND).min(height));
                let mut lines: Vec<Vec<Run>> = Vec::with_capacity((y1 - y0) as usize);
                for y in y0..y1 {
                    let row = map.row(y);
                    match lines.last() {
                        Some(above) if map.row(y - 1) == row => lines.push(above.clone()),
                        _ => lines.push(finish(row_runs(row, &accept), rule)),
                    }
                }
                lines
            })
            .collect();
        RunTable {
            lines: bands.into_iter().flatten().collect(),
        }
    }

    /// Runs along each column. Stripes of columns run in parallel, each sweeping the rows
    /// top to bottom (so memory is read row by row) and acting only where a column changes
    /// between accepted and not.
    pub fn columns(map: &ClassMap, rule: RunRule) -> RunTable {
        const CLOSED: u32 = u32::MAX;
        let accept = accepted(rule.classes);
        let (width, height) = (map.width() as usize, map.height());
        let stripes: Vec<Vec<Vec<Run>>> = (0..width.div_ceil(COLUMN_STRIPE))
            .into_par_iter()
            .map(|stripe| {
                let x0 = stripe * COLUMN_STRIPE;
                let x1 = (x0 + COLUMN_STRIPE).min(width);
                let mut runs = vec![Vec::new(); x1 - x0];
                let mut open = vec![CLOSED; x1 - x0];
                for y in 0..height {
                    let row = &map.row(y)[x0..x1];
                    if y > 0 && &map.row(y - 1)[x0..x1] == row {
                        continue; // no column starts or ends a run here
                    }
                    for ((&class, start), out) in row.iter().zip(&mut open).zip(&mut runs) {
                        let inside = accept[class as usize];
                        if inside != (*start != CLOSED) {
                            if inside {
                                *start = y;
                            } else {
                                out.push([*start, y]);
                                *start = CLOSED;
                            }
                        }
                    }
                }
                for (start, out) in open.iter().zip(&mut runs) {
                    if *start != CLOSED {
                        out.push([*start, height]);
                    }
                }
                runs.into_iter().map(|r| finish(r, rule)).collect()
            })
            .collect();
        RunTable {
            lines: stripes.into_iter().flatten().collect(),
        }
    }

    /// The runs of line `i`.
    #[cfg(test)]
    pub fn line(&self, i: usize) -> &[Run] {
        &self.lines[i]
    }

    /// The run of line `i` that contains position `pos`, if any.
    pub fn run_at(&self, i: usize, pos: u32) -> Option<Run> {
        let runs = self.lines.get(i)?;
        let after = runs.partition_point(|r| r[0] <= pos);
        let run = *runs.get(after.checked_sub(1)?)?;
        (pos < run[1]).then_some(run)
    }

    /// Groups of runs connected through neighbouring lines (runs on lines `i` and `i + 1`
    /// touch when they share a position: 4-connectivity). Each group lists its `(line, run)`
    /// pairs in line order, then along the line; groups are ordered by their first run.
    pub fn groups(&self) -> Vec<Vec<(u32, Run)>> {
        let mut first = Vec::with_capacity(self.lines.len() + 1);
        let mut total = 0;
        for runs in &self.lines {
            first.push(total);
            total += runs.len();
        }
        first.push(total);

        let mut sets = DisjointSets::new(total);
        for i in 1..self.lines.len() {
            let (above, below) = (&self.lines[i - 1], &self.lines[i]);
            let (mut a, mut b) = (0, 0);
            while a < above.len() && b < below.len() {
                let (ra, rb) = (above[a], below[b]);
                if ra[0] < rb[1] && rb[0] < ra[1] {
                    sets.union(first[i - 1] + a, first[i] + b);
                }
                if ra[1] <= rb[1] {
                    a += 1;
                } else {
                    b += 1;
                }
            }
        }

        const NONE: u32 = u32::MAX;
        let mut group_of_root = vec![NONE; total];
        let mut groups: Vec<Vec<(u32, Run)>> = Vec::new();
        for (i, runs) in self.lines.iter().enumerate() {
            for (k, &run) in runs.iter().enumerate() {
                let root = sets.find(first[i] + k);
                if group_of_root[root] == NONE {
                    group_of_root[root] = groups.len() as u32;
                    groups.push(Vec::new());
                }
                groups[group_of_root[root] as usize].push((i as u32, run));
            }
        }
        groups
    }
}

/// A lookup table: `accepted(classes)[class as usize]`.
fn accepted(classes: &[PixelClass]) -> [bool; 5] {
    let mut table = [false; 5];
    for &class in classes {
        table[class as usize] = true;
    }
    table
}

/// The maximal runs of accepted pixels in `row`.
fn row_runs(row: &[PixelClass], accept: &[bool; 5]) -> Vec<Run> {
    let mut runs = Vec::new();
    let mut x = 0;
    while x < row.len() {
        while x < row.len() && !accept[row[x] as usize] {
            x += 1;
        }
        let start = x;
        while x < row.len() && accept[row[x] as usize] {
            x += 1;
        }
        if start < x {
            runs.push([start as u32, x as u32]);
        }
    }
    runs
}

/// Applies `rule` to the maximal runs of one line: joins runs separated by at most
/// `rule.bridge` px, then drops those shorter than `rule.min_len`.
fn finish(mut runs: Vec<Run>, rule: RunRule) -> Vec<Run> {
    if rule.bridge > 0 && runs.len() > 1 {
        let mut joined = 0;
        for i in 1..runs.len() {
            if runs[i][0] - runs[joined][1] <= rule.bridge {
                runs[joined][1] = runs[i][1];
            } else {
                joined += 1;
                runs[joined] = runs[i];
            }
        }
        runs.truncate(joined + 1);
    }
    if rule.min_len > 1 {
        runs.retain(|r| r[1] - r[0] >= rule.min_len);
    }
    runs
}

/// Union–find over run indices; the smaller index is the root, so results do not depend on
/// the order of unions.
struct DisjointSets {
    parent: Vec<usize>,
}

impl DisjointSets {
    fn new(n: usize) -> DisjointSets {
        DisjointSets {
            parent: (0..n).collect(),
        }
    }

    fn find(&mut self, mut i: usize) -> usize {
        let mut root = i;
        while self.parent[root] != root {
            root = self.parent[root];
        }
        while self.parent[i] != root {
            let next = self.parent[i];
            self.parent[i] = root;
            i = next;
        }
        root
    }

    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        self.parent[hi] = lo;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BLOCK: RunRule = RunRule {
        classes: &[PixelClass::Block],
        bridge: 0,
        min_len: 1,
    };

    #[test]
    fn row_runs_bridge_small_gaps_and_drop_short_runs() {
        let noisy = "yyy.yy..yyy...yy.y";
        let cases = [
            (
                noisy,
                0,
                1,
                vec![[0, 3], [4, 6], [8, 11], [14, 16], [17, 18]],
            ),
            (noisy, 2, 1, vec![[0, 11], [14, 18]]),
            (noisy, 2, 6, vec![[0, 11]]),
            (noisy, 1, 4, vec![[0, 6], [14, 18]]),
            ("#.#yyyyyy.y", 1, 6, vec![[3, 11]]),
            ("#.#yyyyy.y", 0, 6, vec![]),
        ];
        for (row, bridge, min_len, expected) in cases {
            let rule = RunRule {
                classes: &[PixelClass::Line],
                bridge,
                min_len,
            };
            let table = RunTable::rows(&ClassMap::drawn(&[row]), rule);
            assert_eq!(
                table.line(0),
                &expected[..],
                "{row} bridge {bridge} min {min_len}"
            );
        }
    }

    #[test]
    fn columns_equal_rows_of_the_transpose() {
        let rows = ["#..##", "##.#.", ".#.##", "....#"];
        let transposed: Vec<String> = (0..5)
            .map(|x| rows.iter().map(|r| r.as_bytes()[x] as char).collect())
            .collect();
        let t: Vec<&str> = transposed.iter().map(String::as_str).collect();
        assert_eq!(
            RunTable::columns(&ClassMap::drawn(&rows), BLOCK),
            RunTable::rows(&ClassMap::drawn(&t), BLOCK)
        );
    }

    #[test]
    fn wide_maps_scan_columns_across_stripes() {
        let width = COLUMN_STRIPE * 2 + 7;
        let row: String = (0..width)
            .map(|x| if x % 3 == 0 { '#' } else { '.' })
            .collect();
        let m = ClassMap::drawn(&[&row, &row, ".".repeat(width).as_str(), &row]);
        let table = RunTable::columns(&m, BLOCK);
        for x in 0..width {
            let expected: &[Run] = if x % 3 == 0 { &[[0, 2], [3, 4]] } else { &[] };
            assert_eq!(table.line(x), expected, "column {x}");
        }
    }

    #[test]
    fn run_at_finds_the_covering_run() {
        let table = RunTable::rows(&ClassMap::drawn(&["..##.###"]), BLOCK);
        let found: Vec<Option<Run>> = (0..9).map(|x| table.run_at(0, x)).collect();
        let (a, b) = (Some([2, 4]), Some([5, 8]));
        assert_eq!(found, vec![None, None, a, a, None, b, b, b, None]);
        assert_eq!(table.run_at(5, 0), None);
    }

    #[test]
    fn groups_follow_four_connectivity_in_raster_order() {
        let m = ClassMap::drawn(&[
            "##..#..#", //
            ".#..#.#.", // the diagonal on the right does not connect
            ".####...", // joins the first two groups (a U shape)
            "......##",
        ]);
        let groups = RunTable::rows(&m, BLOCK).groups();
        let sizes: Vec<u32> = groups
            .iter()
            .map(|g| g.iter().map(|(_, r)| r[1] - r[0]).sum())
            .collect();
        assert_eq!(sizes, vec![9, 1, 1, 2]);
        assert_eq!(groups[0][0], (0, [0, 2]));
        assert_eq!(groups[1], vec![(0, [7, 8])]);
        assert_eq!(groups[2], vec![(1, [6, 7])]);
        assert_eq!(groups[3], vec![(3, [6, 8])]);
    }
}
