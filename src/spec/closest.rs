//! Closest key: an unknown key and the keys a table knows → the one the user probably meant.

/// The known key nearest to `unknown` by edit distance (transpositions count once), if it
/// is near enough to be a typo: at most 1 edit for short keys, 2 for longer ones, or a
/// case-only difference.
pub(crate) fn closest<'a>(
    unknown: &str,
    known: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let limit = if unknown.chars().count() <= 4 { 1 } else { 2 };
    known
        .into_iter()
        .map(|k| {
            let d = if k.eq_ignore_ascii_case(unknown) {
                0
            } else {
                distance(unknown, k)
            };
            (d, k)
        })
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, k)| (d, k))
        .map(|(_, k)| k)
}

/// Optimal string alignment distance: insertions, deletions, substitutions and adjacent
/// transpositions each cost 1.
fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut rows = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in rows.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in rows[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut best = (rows[i - 1][j] + 1)
                .min(rows[i][j - 1] + 1)
                .min(rows[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(rows[i - 2][j - 2] + 1);
            }
            rows[i][j] = best;
        }
    }
    rows[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    const GENERATE: [&str; 7] = [
        "width",
        "height",
        "road_width",
        "strip_width",
        "horizontal_roads",
        "vertical_roads",
        "min_block",
    ];

    #[test]
    fn typos_find_their_key_and_strangers_find_none() {
        let cases = [
            ("road_widht", Some("road_width")),
            ("roadwidth", Some("road_width")),
            ("Width", Some("width")),
            ("heigth", Some("height")),
            ("min_blocks", Some("min_block")),
            ("horizontal", None),
            ("colour", None),
            ("w", None),
        ];
        for (unknown, want) in cases {
            assert_eq!(closest(unknown, GENERATE), want, "{unknown}");
        }
    }

    #[test]
    fn distance_counts_edits() {
        let cases = [
            ("", "abc", 3),
            ("abc", "abc", 0),
            ("abc", "acb", 1),
            ("kitten", "sitting", 3),
        ];
        for (a, b, want) in cases {
            assert_eq!(distance(a, b), want, "{a} {b}");
        }
    }
}
