//! Value checks: a schema-valid palette, buildings and lamps → the problems between values
//! (colours parsing would confuse, duplicate widths, a gap no building fits beside, lamp
//! spacing that removes every lamp).

use std::path::Path;

use super::findings::Findings;
use super::spec::{BUILTIN_FACADES, BuildingsSpec, FacadesSpec, LampsSpec, Palette};
use super::{SpecWorld, resolve};

/// Two palette colours within `tolerance` of each other cannot be told apart by parsing.
pub(crate) fn check_palette(palette: &Palette, findings: &mut Findings<'_, '_>) {
    let colours = [
        ("road", palette.road),
        ("line", palette.line),
        ("block", palette.block),
        ("strip", palette.strip),
    ];
    let tolerance = f64::from(palette.tolerance);
    // The closest pair of default colours that the tolerance alone makes clash.
    let mut tolerance_clash: Option<(f64, &str, &str)> = None;
    for (i, &(name_a, a)) in colours.iter().enumerate() {
        for &(name_b, b) in &colours[i + 1..] {
            let distance =
                a.0.iter()
                    .zip(b.0)
                    .map(|(&x, y)| (f64::from(x) - f64::from(y)).powi(2))
                    .sum::<f64>()
                    .sqrt();
            if distance > tolerance {
                continue;
            }
            let key_a = format!("layout.palette.{name_a}");
            let key_b = format!("layout.palette.{name_b}");
            let (at, other, other_colour, colour) = if findings.written(&key_b) {
                (key_b, key_a, a, b)
            } else if findings.written(&key_a) {
                (key_a, key_b, b, a)
            } else {
                if tolerance_clash.is_none_or(|(d, _, _)| distance < d) {
                    tolerance_clash = Some((distance, name_a, name_b));
                }
                continue;
            };
            let other_colour = findings.shown(&other, other_colour);
            let message = if distance == 0.0 {
                format!(
                    "expected a colour different from {other} ({other_colour}), \
                     found the same colour {colour}"
                )
            } else {
                format!(
                    "expected a colour farther than the tolerance {tolerance} from {other} \
                     ({other_colour}), found {colour} at distance {distance:.1}; \
                     parsing could not tell them apart"
                )
            };
            findings.error(&at, message);
        }
    }
    if let Some((distance, a, b)) = tolerance_clash {
        findings.error(
            "layout.palette.tolerance",
            format!(
                "expected a tolerance below {distance:.1}, the distance between \
                 layout.palette.{a} and layout.palette.{b}, found {tolerance}; parsing could \
                 not tell them apart"
            ),
        );
    }
}

/// Building widths must differ, and the gap must leave room for the smallest building.
pub(crate) fn check_buildings(buildings: &BuildingsSpec, findings: &mut Findings<'_, '_>) {
    // Without explicit widths the facades set the sizes; the facades stage checks them.
    let Some(widths) = &buildings.widths else {
        return;
    };
    for (j, width) in widths.iter().enumerate() {
        if let Some(i) = widths[..j].iter().position(|w| w == width) {
            findings.error(
                &format!("buildings.widths[{j}]"),
                format!(
                    "expected distinct widths, found {width} again (it is also buildings.widths[{i}])"
                ),
            );
        }
    }
    let smallest = widths.iter().copied().fold(f64::INFINITY, f64::min);
    if buildings.gap >= smallest {
        findings.error(
            "buildings.gap",
            format!(
                "expected a gap smaller than the smallest building width ({}), found {}",
                findings.shown("buildings.widths", format!("{smallest} m")),
                findings.shown("buildings.gap", buildings.gap),
            ),
        );
    }
}

/// A facade folder must exist, and so must its floors file.
pub(crate) fn check_facades(
    facades: &FacadesSpec,
    spec_path: &Path,
    world: &dyn SpecWorld,
    findings: &mut Findings<'_, '_>,
) {
    if facades.source == BUILTIN_FACADES {
        if facades.floors.is_some() {
            findings.error(
                "facades.floors",
                "expected no floors file with the builtin facades (they know their floors), \
                 found one; name a facade folder in facades.source to use it",
            );
        }
        return;
    }
    let folder = resolve(spec_path, &facades.source);
    if let Err(problem) = world.folder(&folder) {
        findings.error(
            "facades.source",
            format!(
                "expected \"builtin\" or a facade folder in the CMP layout at {}, found {problem}",
                folder.display()
            ),
        );
        return;
    }
    if let Some(floors) = &facades.floors {
        let file = folder.join(floors);
        if let Err(problem) = world.file(&file) {
            findings.error(
                "facades.floors",
                format!(
                    "expected a floors file at {}, found {problem}",
                    file.display()
                ),
            );
        }
    }
}

/// Lamps closer than `min_distance` are thinned out; beyond the spacing, every neighbour is.
pub(crate) fn check_lamps(lamps: &LampsSpec, findings: &mut Findings<'_, '_>) {
    if lamps.min_distance > lamps.spacing {
        findings.error(
            "lamps.min_distance",
            format!(
                "expected at most lamps.spacing ({}), found {}: lamps {} apart would all be \
                 removed as too close to a neighbour",
                findings.shown("lamps.spacing", lamps.spacing),
                lamps.min_distance,
                lamps.spacing
            ),
        );
    }
}

#[cfg(test)]
mod tests {
    use crate::test_support::FakeWorld;

    fn problems(body: &str) -> Vec<String> {
        let text = format!("version = 1\nname = \"c\"\n[layout.generate]\n{body}");
        FakeWorld::empty()
            .load("city.toml", text)
            .err()
            .unwrap_or_default()
    }

    #[test]
    fn value_problems_name_the_responsible_key() {
        let cases: &[(&str, &[&str])] = &[
            (
                "[layout.palette]\nroad = \"#000000\"\nline = \"#ffffff\"\n",
                &[],
            ),
            (
                "[layout.palette]\nline = \"#808080\"\n",
                &[
                    "layout.palette.line: expected a colour different from layout.palette.road (the default #808080), found the same colour #808080",
                ],
            ),
            (
                "[layout.palette]\nroad = \"#2850dc\"\n",
                &[
                    "layout.palette.road: expected a colour different from layout.palette.block (the default #2850dc), found the same colour #2850dc",
                ],
            ),
            (
                "[layout.palette]\nroad = \"#808080\"\nstrip = \"#858585\"\ntolerance = 5\n",
                &[],
            ),
            (
                "[layout.palette]\nroad = \"#808080\"\nstrip = \"#848484\"\ntolerance = 7\n",
                &[
                    "layout.palette.strip: expected a colour farther than the tolerance 7 from layout.palette.road (#808080), found #848484 at distance 6.9",
                ],
            ),
            (
                "[layout.palette]\ntolerance = 140\n",
                &[
                    "layout.palette.tolerance: expected a tolerance below 118.9, the distance between layout.palette.road and layout.palette.strip, found 140",
                ],
            ),
            (
                "[buildings]\nwidths = [3, 4.5]\ngap = 3\n",
                &[
                    "buildings.gap: expected a gap smaller than the smallest building width (3 m), found 3",
                ],
            ),
            (
                "[buildings]\nwidths = [1.5, 4]\n",
                &[
                    "buildings.gap: expected a gap smaller than the smallest building width (1.5 m), found the default 2",
                ],
            ),
            // Without widths the facades size the buildings: the gap is theirs to check.
            ("[buildings]\ngap = 12\n", &[]),
            (
                "[facades]\nsource = \"no/such/folder\"\n",
                &[
                    "facades.source: expected \"builtin\" or a facade folder in the CMP layout at no/such/folder, found no folder no/such/folder in this fake world",
                ],
            ),
            (
                "[facades]\nfloors = \"floors.txt\"\n",
                &[
                    "facades.floors: expected no floors file with the builtin facades (they know their floors), found one; name a facade folder in facades.source to use it",
                ],
            ),
            (
                "[buildings]\nwidths = [5, 6, 5, 6]\n",
                &[
                    "buildings.widths[2]: expected distinct widths, found 5 again (it is also buildings.widths[0])",
                    "buildings.widths[3]: expected distinct widths, found 6 again (it is also buildings.widths[1])",
                ],
            ),
            ("[lamps]\nspacing = 50\nmin_distance = 50\n", &[]),
            (
                "[lamps]\nspacing = 10\n",
                &[
                    "lamps.min_distance: expected at most lamps.spacing (10), found 20: lamps 10 apart",
                ],
            ),
        ];
        for (body, want) in cases {
            let got = problems(body);
            assert_eq!(got.len(), want.len(), "{body}\n{got:#?}");
            for (g, w) in got.iter().zip(want.iter()) {
                assert!(g.starts_with(w), "{body}\ngot  {g}\nwant {w}…");
            }
        }
    }
}
