//! A road's width in metres → its [`StreetProfile`]: a parking lane at each curb and the
//! driving lanes between it and the centre line, as lane markings and cars use them.
//!
//! A real carriageway: lanes of about [`LANE`] metres and a [`PARKING`] m parking lane at
//! each curb when the half-road has room for both. With the example specs' 0.6 m per pixel
//! a 32 px road is 19.2 m: 2 + 2 lanes of 3.5 m and two 2.6 m parking lanes. At the paper's
//! 1 m per pixel the same road is 32 m: 4 + 4 lanes of 3.35 m.

/// Target width of a driving lane, metres.
pub const LANE: f64 = 3.5;
/// Width of the parking lane along each curb, metres.
pub const PARKING: f64 = 2.6;
/// A driving lane is never narrower than this, metres: below it the half-road is one lane.
pub const MIN_LANE: f64 = 2.8;

/// The lanes of one side of a road (both sides are the same), metres from the centre line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StreetProfile {
    /// Half the road's width: centre line to curb.
    pub half: f64,
    /// Width of the parking lane at the curb (0 when there is no room for one).
    pub parking: f64,
    /// Driving lanes per side, at least 1.
    pub lanes: u32,
    /// Width of each driving lane.
    pub lane: f64,
}

impl StreetProfile {
    /// The profile of a road `width` metres wide.
    pub fn of(width: f64) -> StreetProfile {
        let half = if width.is_finite() {
            width.max(0.0) / 2.0
        } else {
            0.0
        };
        let parking = if half >= PARKING + MIN_LANE {
            PARKING
        } else {
            0.0
        };
        let driving = half - parking;
        // `as` saturates; at least one lane.
        let lanes = ((driving / LANE).round() as u32).max(1);
        let lanes = if lanes > 1 && driving / f64::from(lanes) < MIN_LANE {
            lanes - 1
        } else {
            lanes
        };
        StreetProfile {
            half,
            parking,
            lanes,
            lane: driving / f64::from(lanes),
        }
    }

    /// Distance of driving lane `k`'s middle from the centre line (lane 0 is innermost).
    pub fn lane_centre(&self, k: u32) -> f64 {
        (f64::from(k) + 0.5) * self.lane
    }

    /// Distance of the line between lanes `k` and `k + 1` from the centre line; for the
    /// outermost lane, the parking lane's edge.
    pub fn lane_edge(&self, k: u32) -> f64 {
        f64::from(k + 1) * self.lane
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profiles_of_common_widths() {
        // (width, parking, lanes per side, lane width)
        let cases = [
            (19.2, PARKING, 2, 3.5),
            (32.0, PARKING, 4, 3.35),
            (16.0, PARKING, 1, 5.4),
            (8.0, 0.0, 1, 4.0),
            (4.0, 0.0, 1, 2.0),
            (0.0, 0.0, 1, 0.0),
            (f64::NAN, 0.0, 1, 0.0),
        ];
        for (width, parking, lanes, lane) in cases {
            let p = StreetProfile::of(width);
            assert_eq!(p.parking, parking, "{width}");
            assert_eq!(p.lanes, lanes, "{width}");
            assert!((p.lane - lane).abs() < 1e-9, "{width}");
            assert!((p.lane_edge(p.lanes - 1) + p.parking - p.half).abs() < 1e-9);
        }
    }
}
