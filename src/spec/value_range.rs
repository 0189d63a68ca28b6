//! A spec value that is one number or a range `[a, b]` to draw from: camera heading,
//! pitch, roll, height, distance and angle.

use schemars::{Schema, json_schema};
use serde::{Deserialize, Serialize};

/// One number, or two ends (in either order) of a range a seeded draw picks from.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ValueRange {
    Fixed(f64),
    Between([f64; 2]),
}

impl ValueRange {
    /// The value at `u ∈ [0, 1)` of the way from the low end to the high end; a fixed
    /// value whatever `u`.
    pub fn at(self, u: f64) -> f64 {
        match self {
            ValueRange::Fixed(v) => v,
            ValueRange::Between([a, b]) => {
                let (lo, hi) = (a.min(b), a.max(b));
                lo + (hi - lo) * u
            }
        }
    }

    /// The low and high ends.
    pub fn ends(self) -> [f64; 2] {
        match self {
            ValueRange::Fixed(v) => [v, v],
            ValueRange::Between([a, b]) => [a.min(b), a.max(b)],
        }
    }

    /// Whether both ends are finite.
    pub fn is_finite(self) -> bool {
        match self {
            ValueRange::Fixed(v) => v.is_finite(),
            ValueRange::Between([a, b]) => a.is_finite() && b.is_finite(),
        }
    }
}

/// The schema of a [`ValueRange`] whose values lie in `[min, max]`.
pub(crate) fn range_schema(min: f64, max: f64) -> Schema {
    json_schema!({
        "anyOf": [
            {"type": "number", "minimum": min, "maximum": max},
            {
                "type": "array",
                "items": {"type": "number", "minimum": min, "maximum": max},
                "minItems": 2,
                "maxItems": 2
            }
        ]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_range_draws_between_its_ends_in_either_order() {
        let cases = [
            (ValueRange::Fixed(3.0), 0.7, 3.0, [3.0, 3.0]),
            (
                ValueRange::Between([-60.0, 60.0]),
                0.0,
                -60.0,
                [-60.0, 60.0],
            ),
            (
                ValueRange::Between([-60.0, 60.0]),
                0.75,
                30.0,
                [-60.0, 60.0],
            ),
            (ValueRange::Between([10.0, 2.0]), 0.5, 6.0, [2.0, 10.0]),
        ];
        for (range, u, value, ends) in cases {
            assert_eq!(range.at(u), value, "{range:?} at {u}");
            assert_eq!(range.ends(), ends, "{range:?}");
        }
        assert!(!ValueRange::Between([0.0, f64::NAN]).is_finite());
    }

    #[test]
    fn reads_a_number_or_a_pair() {
        #[derive(Deserialize)]
        struct T {
            a: ValueRange,
            b: ValueRange,
        }
        let t: T = toml::from_str("a = 1.5\nb = [-60, 60]\n").unwrap();
        assert_eq!(t.a, ValueRange::Fixed(1.5));
        assert_eq!(t.b, ValueRange::Between([-60.0, 60.0]));
    }
}
