//! Linear radiance + depth + camera + drawn weather → the radiance under that weather
//! (overcast sky, fog, rain), and the light settings the renderer should take for it.
//!
//! Everything here is image-space, from depth and the camera pose: ids, depth and labels
//! are never touched. Fog is exponential height fog: its extinction is
//! `σ(h) = σ₀ · e^(−h/H)` at height `h`, integrated in closed form along each view ray
//! (`τ = σ(eye) · H · (1 − e^(−s·v_y/H)) / v_y` over a distance `s` with unit direction
//! `v`), so it thickens with distance and thins with height, and sky pixels (infinitely far)
//! fade to the fog's colour near the horizon while the sky overhead shows through.

use rayon::prelude::*;

use super::conditions::Conditions;
use super::noise::splitmix;
use super::rays::{Rays, length};
use super::tone::luminance;
use crate::spec::Weather;

/// What the weather asks of the renderer's lighting (a plain struct the lighting code can
/// consume): the sun's and the sky light's scale, and how dark shadows are (1 = full).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WeatherLight {
    pub sun_scale: f32,
    pub sky_scale: f32,
    pub shadow_strength: f32,
}

/// Share of the sun a cloud at full opacity holds back: a cumulus lets about a sixth
/// through.
const CLOUD_SHADOW: f32 = 0.85;

impl WeatherLight {
    /// This light with `shade` (0–1, [`super::sun_shade`]) of the sun hidden by a cloud:
    /// the sun dimmed, so the shadows it casts fade with it.
    pub fn under_cloud(self, shade: f32) -> WeatherLight {
        WeatherLight {
            sun_scale: self.sun_scale * (1.0 - CLOUD_SHADOW * shade.clamp(0.0, 1.0)),
            ..self
        }
    }
}

/// The light settings for a frame's weather: overcast, fog and rain dim the sun, raise
/// the sky light and soften shadows, the more the stronger the weather.
pub fn weather_light(c: &Conditions) -> WeatherLight {
    let s = c.strength.clamp(0.0, 1.0) as f32;
    let (sun, sky, shadow) = match c.weather {
        Weather::Clear => (0.0, 0.0, 0.0),
        Weather::Overcast => (0.85, 0.8, 0.8),
        Weather::Fog => (0.7, 0.6, 0.7),
        Weather::Rain => (0.9, 0.6, 0.9),
    };
    WeatherLight {
        sun_scale: 1.0 - sun * s,
        sky_scale: 1.0 + sky * s,
        shadow_strength: 1.0 - shadow * s,
    }
}

/// Per-frame constants of the weather pass.
struct Look {
    weather: Weather,
    strength: f32,
    /// Extinction at the eye's height, per metre, and the fog's scale height.
    sigma_eye: f32,
    fog_height: f32,
    fog_colour: [f32; 3],
    /// Luminance of the grey sky at the horizon (overcast and rain).
    grey_sky: f32,
}

impl Look {
    /// The grey sky's colour looking at elevation `sin_elevation` (brighter overhead, as
    /// the CIE overcast sky, softened).
    fn sky(&self, sin_elevation: f32) -> [f32; 3] {
        let l = self.grey_sky * (1.0 + 0.8 * sin_elevation.clamp(0.0, 1.0));
        [0.96 * l, 0.99 * l, 1.04 * l]
    }
}

/// The air's extinction per metre at the ground under `c`, and the scale height (metres)
/// it thins with: fog's drawn density, rain's and haze's fixed ones, 0 in clear air.
fn extinction_at_ground(c: &Conditions) -> (f32, f32) {
    let s = c.strength.clamp(0.0, 1.0) as f32;
    let (sigma0, height) = match c.weather {
        Weather::Clear => (0.0, 100.0),
        Weather::Fog => ((c.fog_density as f32) * s, c.fog_height as f32),
        Weather::Rain => (0.012 * s, 60.0),
        Weather::Overcast => (0.002 * s, 100.0),
    };
    (sigma0, height.max(0.1))
}

/// The extinction per metre of the air at height `eye_height` under `c`: what dims the
/// camera's image with distance there (and a LiDAR's returns, there and back).
pub fn air_extinction(c: &Conditions, eye_height: f64) -> f64 {
    let (sigma0, height) = extinction_at_ground(c);
    f64::from(sigma0 * libm::expf(-(eye_height.max(0.0) as f32) / height))
}

/// Applies the weather of `c` to `linear` (row-major, `width` wide) in place. `depth` is
/// metres along the view axis, 0 for sky; `horizon` the sky's colour at the horizon.
pub(crate) fn apply_weather(
    linear: &mut [[f32; 3]],
    depth: &[f32],
    width: u32,
    rays: &Rays,
    horizon: [f32; 3],
    c: &Conditions,
) {
    if c.weather == Weather::Clear {
        return;
    }
    let s = c.strength.clamp(0.0, 1.0) as f32;
    let h_lum = luminance(horizon);
    let grey = |k: f32| [h_lum * k; 3];
    let mix = |a: [f32; 3], b: [f32; 3], t: f32| [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t);
    let (sigma0, fog_height) = extinction_at_ground(c);
    let (fog_colour, grey_sky) = match c.weather {
        Weather::Fog => (mix(horizon, grey(1.05), 0.8), h_lum),
        Weather::Rain => (grey(0.62), h_lum * 0.6),
        _ => (grey(0.95), h_lum * 0.95),
    };
    let look = Look {
        weather: c.weather,
        strength: s,
        sigma_eye: sigma0 * libm::expf(-rays.eye[1].max(0.0) / fog_height),
        fog_height,
        fog_colour,
        grey_sky,
    };
    // Rain's wet ground reflects the scene as it was before the weather changed it.
    let before = (c.weather == Weather::Rain).then(|| linear.to_vec());
    let w = width.max(1) as usize;
    let rows = linear.len() / w;
    linear.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, colour) in row.iter_mut().enumerate() {
            let i = y * w + x;
            let v = rays.dir(x, y);
            let len = length(v);
            let vy = v[1] / len;
            let d = depth[i];
            let mut c = *colour;
            if d <= 0.0 {
                if look.weather != Weather::Fog {
                    c = mix(c, look.sky(vy), look.strength);
                }
            } else if look.weather == Weather::Rain {
                c = wet(
                    c,
                    &look,
                    rays,
                    before.as_deref().unwrap_or(&[]),
                    (w, rows),
                    v,
                    d,
                );
            }
            let t = transmittance(&look, if d <= 0.0 { f32::INFINITY } else { d * len }, vy);
            *colour = mix(look.fog_colour, c, t);
        }
    });
    if c.weather == Weather::Rain {
        draw_streaks(linear, width, horizon, s, c.seed);
    }
}

/// The share of light that crosses `distance` metres of fog along a ray whose unit
/// direction has vertical component `vy`.
fn transmittance(look: &Look, distance: f32, vy: f32) -> f32 {
    if look.sigma_eye <= 0.0 {
        return 1.0;
    }
    let h = look.fog_height;
    let tau = if vy.abs() < 1e-4 {
        look.sigma_eye * distance
    } else if distance.is_infinite() {
        if vy > 0.0 {
            look.sigma_eye * h / vy
        } else {
            f32::INFINITY
        }
    } else {
        look.sigma_eye * h * (1.0 - libm::expf(-distance * vy / h)) / vy
    };
    libm::expf(-tau.max(0.0))
}

/// A wet surface: darker, and on the ground a mirror-like sheen that grows towards
/// grazing angles (Schlick's Fresnel term), showing the scene mirrored about the horizon
/// blended with the grey sky.
fn wet(
    c: [f32; 3],
    look: &Look,
    rays: &Rays,
    before: &[[f32; 3]],
    (w, h): (usize, usize),
    v: [f32; 3],
    depth: f32,
) -> [f32; 3] {
    let s = look.strength;
    let mut out = c.map(|x| x * (1.0 - 0.35 * s));
    let height = rays.eye[1] + depth * v[1];
    if height > 0.3 {
        return out;
    }
    out = out.map(|x| x * (1.0 - 0.3 * s));
    let len = length(v);
    let cos = (-v[1] / len).clamp(0.0, 1.0);
    let m = 1.0 - cos;
    let fresnel = 0.02 + 0.98 * m * m * m * m * m;
    let mirrored = [v[0], -v[1], v[2]];
    let sky = look.sky(-v[1] / len);
    let seen = rays
        .project_from([0.0; 3], mirrored)
        .filter(|p| p[0] >= 0.0 && p[1] >= 0.0 && (p[0] as usize) < w && (p[1] as usize) < h)
        .map_or(sky, |p| before[p[1] as usize * w + p[0] as usize]);
    let reflection = [0, 1, 2].map(|k| 0.3 * seen[k] + 0.7 * sky[k]);
    let k = (0.5 * s * fresnel).min(1.0);
    [0, 1, 2].map(|i| out[i] * (1.0 - k) + reflection[i] * k)
}

/// Rain streaks in image space: thin, slanted, faint light lines, more with strength,
/// placed from `seed`. Sizes scale with the image height.
fn draw_streaks(linear: &mut [[f32; 3]], width: u32, horizon: [f32; 3], s: f32, seed: u64) {
    let w = width.max(1) as usize;
    let h = linear.len() / w;
    if h == 0 {
        return;
    }
    let scale = h as f32 / 480.0;
    let count = (s * 700.0 * (w * h) as f32 / 307_200.0) as u64;
    let mut counter = 0u64;
    let mut uniform = || {
        counter += 1;
        (splitmix(seed ^ counter.wrapping_mul(0xD1B5_4A32_D192_ED03)) >> 40) as f32
            / (1u64 << 24) as f32
    };
    let wind = (uniform() - 0.5) * 0.5;
    let colour = [0, 1, 2].map(|k| horizon[k] * 0.5 + luminance(horizon) * 0.9);
    for _ in 0..count {
        // Near drops are long and bright, far ones short and faint.
        let near = uniform();
        let length = (8.0 + 34.0 * near * near) * scale;
        let alpha = 0.06 + 0.16 * near * s;
        let slant = wind + (uniform() - 0.5) * 0.06;
        let x0 = uniform() * (w as f32 + 0.4 * h as f32) - 0.2 * h as f32;
        let y0 = uniform() * (h as f32 + length) - length;
        let steps = length.ceil() as usize;
        for t in 0..steps {
            let y = y0 + t as f32;
            if y < 0.0 || y >= h as f32 {
                continue;
            }
            let u = t as f32 / steps as f32;
            let a = alpha * 4.0 * u * (1.0 - u);
            let x = x0 + slant * t as f32;
            let (xi, frac) = (x.floor(), x - x.floor());
            for (xx, share) in [(xi, 1.0 - frac), (xi + 1.0, frac)] {
                if xx < 0.0 || xx >= w as f32 {
                    continue;
                }
                let p = &mut linear[y as usize * w + xx as usize];
                let k = a * share;
                *p = [0, 1, 2].map(|i| p[i] + (colour[i] - p[i]) * k);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn look(sigma: f32) -> Look {
        Look {
            weather: Weather::Fog,
            strength: 1.0,
            sigma_eye: sigma,
            fog_height: 20.0,
            fog_colour: [0.5; 3],
            grey_sky: 0.5,
        }
    }

    #[test]
    fn fog_thickens_with_distance_and_thins_upwards() {
        let l = look(0.03);
        let near = transmittance(&l, 10.0, 0.0);
        let far = transmittance(&l, 100.0, 0.0);
        assert!(near > far && far > 0.0, "{near} {far}");
        // Level rays: Beer–Lambert exactly.
        assert!((far - libm::expf(-3.0)).abs() < 1e-5);
        // Looking up through thinning fog lets more light through than level.
        assert!(transmittance(&l, 100.0, 0.3) > far);
        // The sky overhead shows through; the sky at the horizon is fog.
        assert!(transmittance(&l, f32::INFINITY, 0.9) > 0.5);
        assert!(transmittance(&l, f32::INFINITY, 0.0) < 1e-6);
        assert_eq!(transmittance(&look(0.0), 1000.0, 0.0), 1.0);
    }

    #[test]
    fn weather_light_softens_with_strength() {
        let mut c = Conditions::plain();
        assert_eq!(weather_light(&c).shadow_strength, 1.0);
        c.weather = Weather::Overcast;
        c.strength = 0.5;
        let half = weather_light(&c);
        c.strength = 1.0;
        let full = weather_light(&c);
        assert!(full.shadow_strength < half.shadow_strength && half.shadow_strength < 1.0);
        assert!(full.sun_scale < half.sun_scale && full.sky_scale > half.sky_scale);
    }

    #[test]
    fn a_cloud_over_the_sun_dims_the_sun_only() {
        let mut c = Conditions::plain();
        c.weather = Weather::Overcast;
        c.strength = 0.5;
        let light = weather_light(&c);
        assert_eq!(light.under_cloud(0.0), light);
        let shaded = light.under_cloud(1.0);
        assert!((shaded.sun_scale - light.sun_scale * (1.0 - CLOUD_SHADOW)).abs() < 1e-6);
        assert_eq!(
            (shaded.sky_scale, shaded.shadow_strength),
            (light.sky_scale, light.shadow_strength)
        );
        let half = light.under_cloud(0.5).sun_scale;
        assert!(shaded.sun_scale < half && half < light.sun_scale);
        // Out of range is clamped.
        assert_eq!(light.under_cloud(7.0), shaded);
    }
}
