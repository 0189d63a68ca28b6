//! A map's street lamps → [`Lamp`] sites: each `highway=street_lamp` node at the kerb of
//! the road it lights.

use crate::model::geometry::polygon::{distance, left_normal};
use crate::model::{FeatureKind, Lamp, OsmMap};

/// The farthest a mapped lamp stands from the road it lights, metres: lamps farther out
/// light paths and parks, not a street, and are left out.
pub const REACH: f64 = 25.0;
/// How far behind the kerb a lamp mapped on the carriageway (hung over the street, or
/// mapped on the centreline) stands, metres.
pub const KERB_SETBACK: f64 = 0.5;

/// A lamp at every `street_lamp` feature of `map` within `REACH` of a paved road, in
/// the map's node order, positions in metres (a metre per "pixel"): where the map puts
/// it, or, when that is on the carriageway, `KERB_SETBACK` behind the kerb on the same
/// side of the centreline. It faces the nearest point of that road's centreline, and
/// `road` is that road's index in `map.roads`. A lamp inside a building is left out.
pub fn map_lamps(map: &OsmMap) -> Vec<Lamp> {
    let mut lamps = Vec::new();
    for f in map
        .features
        .iter()
        .filter(|f| f.kind == FeatureKind::StreetLamp)
    {
        let Some((segment, q, d)) = map.nearest_paved(f.at) else {
            break;
        };
        if d > REACH {
            continue;
        }
        let kerb = segment.width / 2.0 + KERB_SETBACK;
        let foot = if d >= kerb {
            f.at
        } else {
            // Out from the centreline on the lamp's side (on the line itself: the right).
            let out = if d > 0.0 {
                [(f.at[0] - q[0]) / d, (f.at[1] - q[1]) / d]
            } else {
                left_normal(segment.a, segment.b).map_or([1.0, 0.0], |n| [-n[0], -n[1]])
            };
            [q[0] + out[0] * kerb, q[1] + out[1] * kerb]
        };
        let to_road = distance(foot, q);
        if map.in_building(foot) || to_road == 0.0 {
            continue;
        }
        lamps.push(Lamp {
            id: lamps.len() as u32,
            position: foot,
            road: segment.road as u32,
            facing: [(q[0] - foot[0]) / to_road, (q[1] - foot[1]) / to_road],
        });
    }
    lamps
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lamps_stand_at_the_kerb_facing_their_road() {
        let lamps = map_lamps(&crate::test_support::street_map());
        // Beside the road: where the map puts it. On the centreline: half the 12 m
        // carriageway and the setback to the right. 60 m from any road: none.
        assert_eq!(
            lamps,
            vec![
                Lamp {
                    id: 0,
                    position: [-100.0, -8.0],
                    road: 0,
                    facing: [0.0, 1.0],
                },
                Lamp {
                    id: 1,
                    position: [-20.0, 6.0 + KERB_SETBACK],
                    road: 0,
                    facing: [0.0, -1.0],
                },
            ]
        );
    }
}
