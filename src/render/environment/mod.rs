//! Image-based lighting for metallic-roughness previews: an HDR environment (the
//! procedural sky Veneer ships, or an equirectangular `.hdr`/`.exr` panorama) on the CPU,
//! and the maps the GPU derives from it ([`EnvironmentMaps`]: a prefiltered specular mip
//! chain, diffuse irradiance and the split-sum BRDF table).

mod maps;
mod panorama;
mod sky;

pub use maps::EnvironmentMaps;

use glam::Vec3;
use std::f32::consts::PI;
use std::path::Path;

/// An environment's radiance in every direction, as a linear-light equirectangular
/// panorama twice as wide as it is high: the top row looks up (+y), the image's centre
/// column looks along −z and its columns turn towards +x to the right.
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    /// What to call it in messages and the editor (`sky`, or the file's name).
    pub name: String,
    width: u32,
    /// Linear RGB radiance, rows from the top.
    texels: Vec<[f32; 3]>,
}

/// Why an environment file could not be used.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {message}")]
pub struct EnvironmentError {
    pub path: String,
    pub message: String,
}

/// The name of the environment [`Environment::sky`] gives (the default).
pub const SKY: &str = "sky";

impl Environment {
    /// The default environment: a procedural sky over a dim ground with two soft studio
    /// panels, smooth everywhere (no sun: the preview's key light is the sun).
    pub fn sky() -> Environment {
        Environment::from_fn(SKY, 512, sky::radiance)
    }

    /// The environment of radiance `radiance(direction)` (unit direction, y up), sampled
    /// at the centres of a `width` × `width / 2` panorama.
    pub fn from_fn(name: &str, width: u32, radiance: impl Fn(Vec3) -> Vec3) -> Environment {
        let width = width.max(2) & !1;
        let height = width / 2;
        let texels = (0..height)
            .flat_map(|row| (0..width).map(move |column| (column, row)))
            .map(|(column, row)| {
                let u = (column as f32 + 0.5) / width as f32;
                let v = (row as f32 + 0.5) / height as f32;
                radiance(direction_of(u, v)).to_array()
            })
            .collect();
        Environment {
            name: name.to_string(),
            width,
            texels,
        }
    }

    /// The environment `name` names: [`SKY`] for the procedural sky, else a panorama
    /// file (see [`Environment::load`]).
    pub fn named(name: &str) -> Result<Environment, EnvironmentError> {
        if name == SKY {
            Ok(Environment::sky())
        } else {
            Environment::load(Path::new(name))
        }
    }

    /// Loads an equirectangular panorama (Radiance `.hdr` or OpenEXR) at least 16
    /// texels wide, averaged down to a power-of-two width of at most 2048. Radiance that is not
    /// finite or is negative becomes 0; radiance past half-float range is clamped to it.
    pub fn load(path: &Path) -> Result<Environment, EnvironmentError> {
        panorama::load(path)
    }

    /// Width and height in texels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.width / 2)
    }

    /// Linear RGB radiance, rows from the top.
    pub fn texels(&self) -> &[[f32; 3]] {
        &self.texels
    }

    /// The radiance arriving from unit `direction`, bilinear between texel centres (the
    /// columns wrap round, the rows stop at the poles).
    pub fn radiance(&self, direction: Vec3) -> Vec3 {
        let (width, height) = self.size();
        let (u, v) = equirect_uv(direction);
        let x = u * width as f32 - 0.5;
        let y = (v * height as f32 - 0.5).clamp(0.0, height as f32 - 1.0);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let texel = |column: f32, row: f32| {
            let column = (column as i64).rem_euclid(i64::from(width)) as u32;
            let row = (row as u32).min(height - 1);
            Vec3::from(self.texels[(row * width + column) as usize])
        };
        let top = texel(x0, y0).lerp(texel(x0 + 1.0, y0), fx);
        let bottom = texel(x0, y0 + 1.0).lerp(texel(x0 + 1.0, y0 + 1.0), fx);
        top.lerp(bottom, fy)
    }
}

/// The unit direction of panorama coordinates (u, v) in [0, 1]² (v down from the top).
pub fn direction_of(u: f32, v: f32) -> Vec3 {
    let (theta, phi) = (v * PI, (u - 0.5) * 2.0 * PI);
    Vec3::new(
        theta.sin() * phi.sin(),
        theta.cos(),
        -theta.sin() * phi.cos(),
    )
}

/// The panorama coordinates (u, v) in [0, 1]² of unit `direction`.
pub fn equirect_uv(direction: Vec3) -> (f32, f32) {
    let u = 0.5 + direction.x.atan2(-direction.z) / (2.0 * PI);
    let v = direction.y.clamp(-1.0, 1.0).acos() / PI;
    (u, v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_and_panorama_coordinates_invert_each_other() {
        for (u, v) in [(0.1, 0.2), (0.5, 0.5), (0.75, 0.9), (0.3, 0.01)] {
            let (u2, v2) = equirect_uv(direction_of(u, v));
            assert!(
                (u - u2).abs() < 1e-5 && (v - v2).abs() < 1e-5,
                "{u},{v} -> {u2},{v2}"
            );
        }
        assert!(direction_of(0.5, 0.5).abs_diff_eq(Vec3::NEG_Z, 1e-6));
        assert!(direction_of(0.75, 0.5).abs_diff_eq(Vec3::X, 1e-6));
        assert!(direction_of(0.5, 0.0).abs_diff_eq(Vec3::Y, 1e-6));
    }

    #[test]
    fn radiance_interpolates_the_function_the_panorama_sampled() {
        let gradient = |d: Vec3| Vec3::new(1.0 + d.y, 1.0 + d.x, 1.0 - d.z);
        let environment = Environment::from_fn("gradient", 256, gradient);
        for d in [
            Vec3::new(0.3, 0.5, -0.8),
            Vec3::new(-0.9, 0.1, 0.4),
            Vec3::Z,
        ] {
            let d = d.normalize();
            let error = (environment.radiance(d) - gradient(d)).abs().max_element();
            assert!(error < 0.02, "{d}: {error}");
        }
    }

    #[test]
    fn the_sky_is_brighter_above_than_below_and_finite_everywhere() {
        let sky = Environment::sky();
        assert!(
            sky.texels()
                .iter()
                .flatten()
                .all(|c| c.is_finite() && *c >= 0.0)
        );
        assert!(sky.radiance(Vec3::Y).length() > 2.0 * sky.radiance(Vec3::NEG_Y).length());
    }
}
