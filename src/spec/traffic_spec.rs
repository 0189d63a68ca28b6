//! Moving traffic: the `[traffic]` table.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::findings::Findings;

/// Traffic that moves. With this table, the cars standing in the lanes and the ridden
/// bicycles drive along their lanes on a timed drive (a roads camera with `fps`): each
/// keeps its lane and goes straight on, follows the one ahead (Newell's car-following
/// model), stops at a junction's stop line while its road has no green and at the end of
/// its road. Walking people walk on along their sidewalks; people on and waiting at zebra
/// crossings cross. Every junction runs one signal cycle (the signal heads show it, lamp
/// by lamp); every position is a function of the seed and the time alone, so any frame
/// renders on its own. Parked cars and bicycles, standing people and everything else stand
/// still. Cameras without a time see the traffic as it stands at time 0.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TrafficSpec {
    /// The range each vehicle's cruising speed is drawn from, km/h: `[min, max]`.
    #[serde(default = "default_car_kmh")]
    #[schemars(length(equal = 2))]
    pub car_kmh: [f64; 2],
    /// The range each ridden bicycle's speed is drawn from, km/h: `[min, max]`.
    #[serde(default = "default_bicycle_kmh")]
    #[schemars(length(equal = 2))]
    pub bicycle_kmh: [f64; 2],
    /// The range each walking person's speed is drawn from, km/h: `[min, max]`. People
    /// walk along the sidewalks (stopping short of what stands in their way and of each
    /// other) and across the zebra crossings (while the road they cross has red).
    #[serde(default = "default_walk_kmh")]
    #[schemars(length(equal = 2))]
    pub walk_kmh: [f64; 2],
    /// A junction's whole signal cycle, seconds: each road green, amber (3 s), then red
    /// for all (2 s), in turn.
    #[serde(default = "default_cycle")]
    #[schemars(range(min = 20.0, max = 600.0))]
    pub cycle: f64,
}

impl Default for TrafficSpec {
    fn default() -> Self {
        TrafficSpec {
            car_kmh: default_car_kmh(),
            bicycle_kmh: default_bicycle_kmh(),
            walk_kmh: default_walk_kmh(),
            cycle: default_cycle(),
        }
    }
}

fn default_car_kmh() -> [f64; 2] {
    [25.0, 45.0]
}
fn default_bicycle_kmh() -> [f64; 2] {
    [12.0, 20.0]
}
fn default_walk_kmh() -> [f64; 2] {
    [3.6, 5.4]
}
fn default_cycle() -> f64 {
    40.0
}

/// The speeds' ranges: each from 1 to 130 km/h, its min not above its max.
pub(crate) fn check_traffic(traffic: Option<&TrafficSpec>, findings: &mut Findings<'_, '_>) {
    let Some(traffic) = traffic else {
        return;
    };
    for (key, [min, max]) in [
        ("traffic.car_kmh", traffic.car_kmh),
        ("traffic.bicycle_kmh", traffic.bicycle_kmh),
        ("traffic.walk_kmh", traffic.walk_kmh),
    ] {
        if !(1.0..=130.0).contains(&min) || !(1.0..=130.0).contains(&max) {
            findings.error(
                key,
                format!("expected speeds from 1 to 130 km/h, found [{min}, {max}]"),
            );
        } else if min > max {
            findings.error(
                key,
                format!("expected [min, max] with min <= max, found [{min}, {max}]"),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::test_support::FakeWorld;

    /// The spec's `[traffic]`, or its problems as `key: message`.
    fn traffic(body: &str) -> Result<Option<super::TrafficSpec>, Vec<String>> {
        let text = format!("version = 1\nname = \"c\"\n[layout.generate]\n{body}");
        FakeWorld::empty()
            .load("city.toml", text)
            .map(|spec| spec.traffic)
    }

    #[test]
    fn traffic_is_absent_by_default_and_checks_its_speeds() {
        assert_eq!(traffic(""), Ok(None));
        assert_eq!(
            traffic("[traffic]\n"),
            Ok(Some(super::TrafficSpec::default()))
        );
        assert_eq!(
            traffic("[traffic]\ncar_kmh = [50, 30]\n"),
            Err(vec![
                "traffic.car_kmh: expected [min, max] with min <= max, found [50, 30]".to_owned()
            ])
        );
        assert_eq!(
            traffic("[traffic]\nbicycle_kmh = [0, 20]\n"),
            Err(vec![
                "traffic.bicycle_kmh: expected speeds from 1 to 130 km/h, found [0, 20]".to_owned()
            ])
        );
        for bad in ["cycle = 5", "cycle = 1000", "lanes = 2", "car_kmh = [30]"] {
            let found = traffic(&format!("[traffic]\n{bad}\n"));
            assert!(found.is_err(), "{bad}: {found:?}");
        }
    }
}
