//! Sun + turbidity + lamps + lit windows → [`Lighting`] of a frame: sky, ambient from
//! above and below, the sun with its colour through the air, shadows, point lights,
//! emission and lit windows, and the exposure of the default development.
//!
//! Units: a white diffuse surface under a unit light shows radiance 1; the high sun is
//! about 1, the daylight sky's ambient about 0.3. Everything is linear RGB and HDR.

use serde::{Deserialize, Serialize};

use super::sky::{Sky, smoothstep};
use super::sun::{self, Sun};
use super::{LitWindows, develop};

/// A point light, all round or in a beam (what it adds: `render::point_lights`).
/// On its axis, facing it and much nearer than `near`, a surface receives `colour`;
/// farther, inverse-square, `colour · near² / (near² + d²)`, smoothly cut to zero at
/// `range` by `(1 − (d / range)²)²`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Light {
    pub position: [f32; 3],
    pub colour: [f32; 3],
    pub range: f32,
    /// Metres within which the light stops brightening (about the size of the source
    /// and its glare); 0 for no inverse-square falloff.
    pub near: f32,
    /// The beam's axis (any length), or zero for a light shining all round.
    pub aim: [f32; 3],
    /// Cosine of the angle from the axis at which the beam reaches zero; it brightens
    /// linearly in the cosine towards the axis. Ignored without an `aim`.
    pub edge: f32,
    /// A dipped headlight's cut-off: the sine of the elevation (from the horizontal,
    /// seen from the light) above which it sends nothing, fading in over
    /// [`CUTOFF_BAND`] below it. None for a light without one.
    #[serde(default)]
    pub cutoff: Option<f32>,
}

/// Sine of elevation over which a [`Light::cutoff`] goes from full light to none: about
/// 0.9°, a sharp line on a wall ahead, as a dipped beam's is.
pub const CUTOFF_BAND: f32 = 0.015;

impl Light {
    /// A light shining all round, without inverse-square falloff (only the cut to zero at
    /// `range`).
    pub fn point(position: [f32; 3], colour: [f32; 3], range: f32) -> Light {
        Light {
            position,
            colour,
            range,
            near: 0.0,
            aim: [0.0; 3],
            edge: -1.0,
            cutoff: None,
        }
    }

    /// A street lamp's shielded head at `position`: a downward beam that still reaches
    /// a little above the horizontal (the head's diffuser) and nothing higher, so the
    /// crowns of the trees above it stay dark; `LAMP_NEAR` of near field.
    pub fn street_lamp(position: [f32; 3], colour: [f32; 3], range: f32) -> Light {
        Light {
            position,
            colour,
            range,
            near: LAMP_NEAR,
            aim: [0.0, -1.0, 0.0],
            edge: -0.25,
            cutoff: None,
        }
    }
}

/// Everything about a frame's light; all colours linear RGB.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Lighting {
    /// Radiance where nothing is drawn.
    pub sky: Sky,
    /// Ambient light on an upward surface (the sky's irradiance ÷ π).
    pub ambient: [f32; 3],
    /// Ambient light on a downward surface (light bounced off the ground).
    pub ground_ambient: [f32; 3],
    /// Towards the sun, unit length.
    pub sun_direction: [f32; 3],
    /// Zero at night.
    pub sun_colour: [f32; 3],
    /// Whether the sun casts shadows (a shadow map of the whole scene).
    pub shadows: bool,
    /// Largest side of the shadow map, texels ([`MAX_SHADOW_MAP_SIDE`] for street frames;
    /// an image that sees the whole city at a coarser ground sampling needs fewer).
    pub shadow_map_side: u32,
    /// How dark shadows are: 1 keeps none of the sun in shadow, 0 casts none. Overcast,
    /// fog and rain lower it (the sun's disk is diffused; see `sensor::weather_light`).
    pub shadow_strength: f32,
    /// Strength of the screen-space ambient occlusion on the ambient light, 0–1 (0 is off).
    pub ambient_occlusion: f32,
    /// Lamp lights after dusk (empty by day).
    pub lights: Vec<Light>,
    /// The lights that move with an object: `(index in lights, instance id)` (a car's
    /// lamps, a lamp over its number plate), for moving traffic ([`Lighting::moved`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub carried: Vec<(u32, u32)>,
    /// Scale of the materials' emissive colours: 1 at night (lamp heads glow), 0 by day.
    pub emission: f32,
    /// Lit windows after dusk; `None` by day.
    pub windows: Option<LitWindows>,
    /// Exposure of the default development ([`develop::develop`]) of `Frame::rgb`.
    pub exposure: f32,
}

pub use super::shadow_map::MAX_SIDE as MAX_SHADOW_MAP_SIDE;

/// The night sky's colour.
pub const NIGHT_SKY: [f32; 3] = [0.005, 0.007, 0.02];
/// Albedo of the ground, for the light it bounces up.
const GROUND_ALBEDO: f32 = 0.2;
/// Colour of a street lamp at full strength: with `LAMP_NEAR`, about 0.8 (most of the
/// noon sun's strength) on the pavement under the head, an eighth of that 8 m to the side.
pub const LAMP_COLOUR: [f32; 3] = [3.4, 2.6, 1.7];
/// Near field of a street lamp, metres.
pub const LAMP_NEAR: f32 = 4.0;
/// Default strength of the ambient occlusion.
pub const AMBIENT_OCCLUSION: f32 = 1.0;
/// Colour of a lit window.
pub const WINDOW_COLOUR: [f32; 3] = [1.0, 0.82, 0.5];

impl Lighting {
    /// This lighting for a view from the air with a shadow map of `shadow_map_side`
    /// texels: without ambient occlusion, whose metre-wide creases are a pixel or two from
    /// the air and would cost the cold build a tenth of a second.
    pub fn from_the_air(self, shadow_map_side: u32) -> Lighting {
        Lighting {
            ambient_occlusion: 0.0,
            shadow_map_side,
            ..self
        }
    }

    /// This lighting under a frame's weather (the sun and the sky light scaled by
    /// `sun_scale` and `sky_scale`, shadows weakened by `shadow_strength`) and with `extra`
    /// lights (a camera car's headlights); `None` when that changes nothing.
    pub fn under_weather(
        &self,
        sun_scale: f32,
        sky_scale: f32,
        shadow_strength: f32,
        extra: Vec<Light>,
    ) -> Option<Lighting> {
        let clear = sun_scale == 1.0 && sky_scale == 1.0 && shadow_strength == 1.0;
        if clear && extra.is_empty() {
            return None;
        }
        let mut out = self.clone();
        out.sun_colour = out.sun_colour.map(|c| c * sun_scale);
        out.ambient = out.ambient.map(|c| c * sky_scale);
        out.shadow_strength *= shadow_strength;
        out.lights.extend(extra);
        Some(out)
    }

    /// This lighting with the lights objects carry moved with them by `movement`; `None`
    /// when none of them moved.
    pub fn moved(&self, movement: &crate::model::Movement) -> Option<Lighting> {
        let shifted: Vec<(usize, [f64; 3])> = self
            .carried
            .iter()
            .map(|&(light, id)| (light as usize, movement.offset(id)))
            .filter(|(light, offset)| *light < self.lights.len() && *offset != [0.0; 3])
            .collect();
        if shifted.is_empty() {
            return None;
        }
        let mut out = self.clone();
        for (light, offset) in shifted {
            let p = &mut out.lights[light].position;
            for k in 0..3 {
                p[k] += offset[k] as f32;
            }
        }
        Some(out)
    }

    /// A clear day: the `day` preset's sun (high, south-east), turbidity 3, shadows, no
    /// lamps.
    pub fn day() -> Lighting {
        Lighting::from_sun(&sun::DAY, 3.0, Vec::new(), None)
    }

    /// Night: a dark sky, a faint ambient, no sun, the given lamp lights, glowing emissive
    /// materials and (optionally) lit windows.
    pub fn night(lights: Vec<Light>, windows: Option<LitWindows>) -> Lighting {
        Lighting::from_sun(&sun::NIGHT, 3.0, lights, windows)
    }

    /// The light of `sun` through air of `turbidity`. `lights` (at full strength) and
    /// `windows` come on as the sun sets: off above 10° of elevation, fully on below 3°.
    pub fn from_sun(
        sun: &Sun,
        turbidity: f64,
        lights: Vec<Light>,
        windows: Option<LitWindows>,
    ) -> Lighting {
        let sun_colour = sun_colour(sun.elevation, turbidity);
        let sky = Sky::daylight(sun, turbidity, sun_colour, NIGHT_SKY);
        let night_ambient = [0.02, 0.022, 0.03];
        let ambient: [f32; 3] = std::array::from_fn(|k| sky.ambient_up[k].max(night_ambient[k]));
        let d = sun.direction();
        let rise = d[1].max(0.0) as f32;
        let ground_ambient: [f32; 3] =
            std::array::from_fn(|k| GROUND_ALBEDO * (ambient[k] + sun_colour[k] * rise));
        let dark = (1.0 - smoothstep(3.0, 10.0, sun.elevation)) as f32;
        let lights = if dark > 0.0 {
            lights
                .into_iter()
                .map(|l| Light {
                    colour: l.colour.map(|c| c * dark),
                    ..l
                })
                .collect()
        } else {
            Vec::new()
        };
        let windows = windows.filter(|_| dark > 0.0).map(|w| LitWindows {
            colour: w.colour.map(|c| c * dark),
            ..w
        });
        let key = develop::luminance(ambient) + develop::luminance(sun_colour) * rise;
        let exposure = scene_exposure(key);
        Lighting {
            sky,
            ambient,
            ground_ambient,
            sun_direction: d.map(|v| v as f32),
            sun_colour,
            shadows: true,
            shadow_map_side: MAX_SHADOW_MAP_SIDE,
            shadow_strength: 1.0,
            ambient_occlusion: AMBIENT_OCCLUSION,
            lights,
            carried: Vec::new(),
            emission: dark,
            windows,
            exposure,
        }
    }
}

/// Daylight (the `key`: luminance of the light on an upward surface) above which the
/// exposure brings the key to 0.9, as a camera by day does.
const BRIGHT_KEY: f32 = 0.36;

/// The default development's exposure for daylight `key`: `0.9 / key` (about 1 by day, at
/// least 0.75) down to [`BRIGHT_KEY`], where it reaches 2.5; in dimmer light it falls again
/// as the fourth root of the key, to about 1.6 at dusk and 1.2 at night. A camera at night
/// exposes for the lamps, not for the dark: unlit walls and the sky stay near black, the
/// lamps' pools (about 1, the noon sun's strength) bright, lit windows glowing.
pub fn scene_exposure(key: f32) -> f32 {
    let key = if key.is_finite() { key.max(1e-4) } else { 1.0 };
    if key >= BRIGHT_KEY {
        (0.9 / key).max(0.75)
    } else {
        0.9 / BRIGHT_KEY * libm::sqrtf(libm::sqrtf(key / BRIGHT_KEY))
    }
}

/// The direct sun's colour at `elevation` degrees: extinction along the air mass
/// (Kasten and Young 1989) with Rayleigh and aerosol optical depths per channel (the
/// aerosol part grows with turbidity), fading out as the sun sets.
pub fn sun_colour(elevation: f64, turbidity: f64) -> [f32; 3] {
    if elevation <= -1.0 {
        return [0.0; 3];
    }
    let e = elevation.max(0.0);
    let mass = 1.0 / (libm::sin(e.to_radians()) + 0.50572 * libm::pow(e + 6.07995, -1.6364));
    let aerosol = (turbidity - 1.0).max(0.0) * 0.5;
    let depth = [
        0.04 + 0.05 * aerosol,
        0.09 + 0.055 * aerosol,
        0.20 + 0.065 * aerosol,
    ];
    let fade = smoothstep(-1.0, 1.0, elevation);
    depth.map(|t| (1.15 * libm::exp(-t * mass) * fade) as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn day_has_a_unit_sun_and_no_emission_and_night_no_sun_and_a_darker_sky() {
        let day = Lighting::day();
        let d = day.sun_direction;
        let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        assert!((len2 - 1.0).abs() < 1e-5, "{len2}");
        assert_eq!(day.emission, 0.0);
        assert!(day.lights.is_empty());
        let night = Lighting::night(Vec::new(), None);
        assert_eq!(night.sun_colour, [0.0; 3]);
        assert_eq!(night.emission, 1.0);
        let (n, s) = (
            night.sky.radiance([0.0, 1.0, 0.0]),
            day.sky.radiance([0.0, 1.0, 0.0]),
        );
        assert!(n.iter().zip(s).all(|(n, d)| *n < d));
        assert!(day.ambient.iter().all(|&a| a > 0.1), "{:?}", day.ambient);
    }

    #[test]
    fn exposure_lifts_dusk_and_night_less_than_their_darkness() {
        let day = Lighting::day().exposure;
        let dusk = Lighting::from_sun(&sun::DUSK, 3.0, Vec::new(), None).exposure;
        let night = Lighting::night(Vec::new(), None).exposure;
        assert!((0.75..1.0).contains(&day), "{day}");
        // Continuous at the bright key, and falling on both sides of it.
        let peak = scene_exposure(BRIGHT_KEY);
        assert!((scene_exposure(BRIGHT_KEY * 0.999) - peak).abs() < 1e-3);
        assert!(scene_exposure(0.2) < peak && scene_exposure(0.5) < peak);
        assert!(night < dusk && dusk < peak, "{night} {dusk} {peak}");
        assert!((1.0..1.5).contains(&night), "{night}");
        // The night ambient ends near black: below 1 % after exposure.
        assert!(develop::luminance(Lighting::night(Vec::new(), None).ambient) * night < 0.03);
        assert_eq!(scene_exposure(f32::NAN), scene_exposure(1.0));
    }

    #[test]
    fn the_sun_reddens_and_dims_as_it_sets() {
        let noon = sun_colour(60.0, 3.0);
        let low = sun_colour(3.0, 3.0);
        assert!(noon[2] > 0.6 && noon[0] > 0.85, "{noon:?}");
        assert!(low[0] > 2.0 * low[2] && low[0] < noon[0], "{low:?}");
        assert_eq!(sun_colour(-5.0, 3.0), [0.0; 3]);
        let hazy = sun_colour(30.0, 8.0);
        assert!(hazy[1] < sun_colour(30.0, 2.0)[1]);
    }
}
