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
    strsim::osa_distance(a, b)
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
