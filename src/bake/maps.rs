//! Turning rendered material outputs into texture maps, and writing them.

use super::Format;
use image::ImageEncoder;
use std::path::Path;

/// A texture map a bake can write.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Map {
    /// Base colour (RGB; the EXR keeps alpha in A).
    Albedo,
    /// Opacity (grey).
    Alpha,
    /// Displacement along the normal (grey; PNG clamps to [0, 1], EXR keeps the value).
    Height,
    /// Tangent-space normals from the height field and the bump output.
    Normal,
    /// Specular colour (RGB).
    Specular,
    /// Roughness from the Blinn-Phong shininess n: sqrt(2 / (n + 2)) (grey).
    Roughness,
}

impl Map {
    /// Every map, as named on the command line.
    pub const ALL: [Map; 6] = [
        Map::Albedo,
        Map::Alpha,
        Map::Height,
        Map::Normal,
        Map::Specular,
        Map::Roughness,
    ];

    /// The map's name in file names and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Map::Albedo => "albedo",
            Map::Alpha => "alpha",
            Map::Height => "height",
            Map::Normal => "normal",
            Map::Specular => "specular",
            Map::Roughness => "roughness",
        }
    }
}

/// Which way a normal map's green channel points.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum NormalConvention {
    /// Green up (towards the top of the image): OpenGL, Blender, Godot, Unity.
    OpenGl,
    /// Green down: DirectX, Unreal.
    DirectX,
}

/// Turns rendered outputs into `map`, in place: each pixel becomes the four values to
/// write (RGB plus alpha for EXR). `spacing` is the plane distance between pixels in x and z.
pub fn convert(
    map: Map,
    mut pixels: Vec<[f32; 4]>,
    size: u32,
    spacing: (f64, f64),
    convention: NormalConvention,
) -> Vec<[f32; 4]> {
    match map {
        Map::Albedo => {}
        Map::Alpha => pixels.iter_mut().for_each(|p| *p = [p[3], p[3], p[3], 1.0]),
        Map::Height => pixels.iter_mut().for_each(|p| *p = [p[0], p[0], p[0], 1.0]),
        Map::Specular => pixels.iter_mut().for_each(|p| p[3] = 1.0),
        Map::Roughness => pixels.iter_mut().for_each(|p| {
            let roughness = (2.0 / (p[3].max(0.0) + 2.0)).sqrt();
            *p = [roughness, roughness, roughness, 1.0];
        }),
        Map::Normal => {
            let heights: Vec<f32> = pixels.iter().map(|p| p[0]).collect();
            normal_map(&heights, &mut pixels, size, spacing, convention);
        }
    }
    pixels
}

/// Tangent-space normals of the height field `heights` (row-major, size²), perturbed by
/// each pixel's bump (lanes 1..4 of `pixels`), encoded as 0.5 + 0.5·n into `pixels`.
/// Central differences inside, one-sided at the edges.
pub fn normal_map(
    heights: &[f32],
    pixels: &mut [[f32; 4]],
    size: u32,
    spacing: (f64, f64),
    convention: NormalConvention,
) {
    let n = size as usize;
    let at = |i: usize, j: usize| heights[j * n + i];
    let (dx, dz) = (spacing.0 as f32, spacing.1 as f32);
    for j in 0..n {
        for i in 0..n {
            let (left, right) = (i.saturating_sub(1), (i + 1).min(n - 1));
            let (up, down) = (j.saturating_sub(1), (j + 1).min(n - 1));
            let slope_x = (at(right, j) - at(left, j)) / (dx * (right - left).max(1) as f32);
            let slope_z = (at(i, down) - at(i, up)) / (dz * (down - up).max(1) as f32);
            let pixel = &mut pixels[j * n + i];
            // Object space (y up) with the bump added, as the preview lights it.
            let normal = glam::Vec3::new(-slope_x, 1.0, -slope_z).normalize()
                + glam::Vec3::new(pixel[1], pixel[2], pixel[3]);
            let normal = normal.normalize_or(glam::Vec3::Y);
            // Tangent space: x along +x (right), y towards the top of the image (-z), z up.
            let green = match convention {
                NormalConvention::OpenGl => -normal.z,
                NormalConvention::DirectX => normal.z,
            };
            *pixel = [
                0.5 + 0.5 * normal.x,
                0.5 + 0.5 * green,
                0.5 + 0.5 * normal.y,
                1.0,
            ];
        }
    }
}

/// Grows covered texels (not NaN) into uncovered ones, `passes` texels outwards, each
/// uncovered texel taking the mean of its covered 4-neighbours; what stays uncovered
/// becomes 0.
pub fn fill_uncovered(pixels: &mut [[f32; 4]], size: u32, passes: u32) {
    let n = size as usize;
    let covered = |p: &[f32; 4]| !p[0].is_nan();
    for _ in 0..passes {
        let mut grown = Vec::new();
        for j in 0..n {
            for i in 0..n {
                if covered(&pixels[j * n + i]) {
                    continue;
                }
                let neighbours = [
                    (i.wrapping_sub(1), j),
                    (i + 1, j),
                    (i, j.wrapping_sub(1)),
                    (i, j + 1),
                ];
                let (mut sum, mut count) = ([0.0f32; 4], 0.0f32);
                for (x, y) in neighbours.into_iter().filter(|&(x, y)| x < n && y < n) {
                    let p = pixels[y * n + x];
                    if covered(&p) {
                        (0..4).for_each(|k| sum[k] += p[k]);
                        count += 1.0;
                    }
                }
                if count > 0.0 {
                    grown.push((j * n + i, sum.map(|s| s / count)));
                }
            }
        }
        if grown.is_empty() {
            break;
        }
        for (index, value) in grown {
            pixels[index] = value;
        }
    }
    pixels
        .iter_mut()
        .filter(|p| p[0].is_nan())
        .for_each(|p| *p = [0.0; 4]);
}

/// Writes a converted map (atomically, streaming into the temporary file).
pub fn write(path: &Path, pixels: Vec<[f32; 4]>, size: u32, format: Format) -> std::io::Result<()> {
    let error = |e: image::ImageError| std::io::Error::other(e.to_string());
    match format {
        Format::Png8 => {
            let rgb: Vec<u8> = pixels
                .iter()
                .flat_map(|p| [p[0], p[1], p[2]])
                .map(|v| (255.0 * v.clamp(0.0, 1.0)).round() as u8)
                .collect();
            drop(pixels);
            crate::fsutil::write_atomic_with(path, |file| {
                image::codecs::png::PngEncoder::new(file)
                    .write_image(&rgb, size, size, image::ExtendedColorType::Rgb8)
                    .map_err(error)
            })
        }
        Format::Png16 => {
            let rgb: Vec<u16> = pixels
                .iter()
                .flat_map(|p| [p[0], p[1], p[2]])
                .map(|v| (65535.0 * v.clamp(0.0, 1.0)).round() as u16)
                .collect();
            drop(pixels);
            crate::fsutil::write_atomic_with(path, |file| {
                let encoder = image::codecs::png::PngEncoder::new(file);
                encoder
                    .write_image(
                        bytemuck::cast_slice(&rgb),
                        size,
                        size,
                        image::ExtendedColorType::Rgb16,
                    )
                    .map_err(error)
            })
        }
        Format::Exr => {
            let floats: Vec<f32> = bytemuck::cast_vec(pixels);
            crate::fsutil::write_atomic_with(path, |file| {
                let encoder = image::codecs::openexr::OpenExrEncoder::new(file);
                encoder
                    .write_image(
                        bytemuck::cast_slice(&floats),
                        size,
                        size,
                        image::ExtendedColorType::Rgba32F,
                    )
                    .map_err(error)
            })
        }
    }
}
