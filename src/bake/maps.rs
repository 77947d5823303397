//! Turning rendered material outputs into texture maps.

use crate::graph::Shading;
use crate::render::FlatChannels;
use rayon::prelude::*;

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
    /// Roughness (grey): the material's roughness under metallic-roughness shading;
    /// under Blinn-Phong, from the shininess n as sqrt(2 / (n + 2)).
    Roughness,
    /// Metallic (grey).
    Metallic,
    /// Ambient occlusion (grey).
    Occlusion,
    /// Emission × emission strength (RGB; PNG clamps to [0, 1], EXR keeps the value).
    Emission,
    /// Occlusion, roughness and metallic packed in R, G and B, as glTF and engines read them.
    Orm,
}

impl Map {
    /// Every map, as named on the command line.
    pub const ALL: [Map; 10] = [
        Map::Albedo,
        Map::Alpha,
        Map::Height,
        Map::Normal,
        Map::Specular,
        Map::Roughness,
        Map::Metallic,
        Map::Occlusion,
        Map::Emission,
        Map::Orm,
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
            Map::Metallic => "metallic",
            Map::Occlusion => "occlusion",
            Map::Emission => "emission",
            Map::Orm => "orm",
        }
    }

    /// The material outputs the map is made from.
    pub fn channels(self) -> FlatChannels {
        match self {
            Map::Albedo | Map::Alpha => FlatChannels::AlbedoAlpha,
            Map::Specular => FlatChannels::SpecularShininess,
            Map::Height | Map::Normal => FlatChannels::HeightBump,
            Map::Roughness | Map::Metallic | Map::Occlusion | Map::Orm => {
                FlatChannels::MetallicRoughness
            }
            Map::Emission => FlatChannels::Emission,
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

/// Turns rendered material outputs into a map's pixels (RGB, plus alpha for EXR), band
/// by band in place, on every core. A normal map needs the heights above and below each
/// row, so each band's last row waits, copied, for the next band (or [`Converter::finish`]).
pub struct Converter {
    map: Map,
    shading: Shading,
    size: usize,
    /// Plane distance between pixels in x and z.
    spacing: (f32, f32),
    convention: NormalConvention,
    /// Heights of image rows `first_height_row..`: the two rows before the current band,
    /// then the band's.
    heights: Vec<f32>,
    first_height_row: usize,
    /// The image row the next band starts at.
    next_row: usize,
    /// A band's last row, unconverted, while it waits for the row below.
    held: Vec<[f32; 4]>,
    /// For a tile: the heights of the rows just above the image and just below it. Its
    /// normals then take their differences across the edges (wrapping left and right).
    beyond: Option<(Vec<f32>, Vec<f32>)>,
}

impl Converter {
    /// A converter for a `size`² `map` of a material shaded by `shading` whose pixels
    /// lie `spacing` apart on the plane.
    pub fn new(
        map: Map,
        shading: Shading,
        size: u32,
        spacing: (f64, f64),
        convention: NormalConvention,
    ) -> Converter {
        Converter {
            map,
            shading,
            size: size as usize,
            spacing: (spacing.0 as f32, spacing.1 as f32),
            convention,
            heights: Vec::new(),
            first_height_row: 0,
            next_row: 0,
            held: Vec::new(),
            beyond: None,
        }
    }

    /// The converter of one tile of a repeating texture, whose heights continue in
    /// `above` (the row above the top edge, which repeats the bottom row) and `below`
    /// (the row below the bottom edge): normals take central differences across every
    /// edge, wrapping left and right, so the normal map tiles too.
    pub fn tiling(mut self, above: Vec<f32>, below: Vec<f32>) -> Converter {
        self.beyond = Some((above, below));
        self
    }

    /// Converts the next band of whole rows in place and passes every finished row on to
    /// `emit`, in order.
    pub fn band<E, F>(&mut self, band: &mut [[f32; 4]], emit: &mut F) -> Result<(), E>
    where
        F: FnMut(&[[f32; 4]]) -> Result<(), E> + ?Sized,
    {
        let n = self.size;
        if self.map != Map::Normal {
            let (map, shading) = (self.map, self.shading);
            band.par_chunks_mut(n)
                .for_each(|row| row.iter_mut().for_each(|p| *p = pixel(map, shading, *p)));
            return emit(band);
        }
        let rows = band.len() / n;
        let first = self.next_row;
        // Keep the heights of the two rows above the band (the held row and the one above it).
        let keep = first.saturating_sub(2).max(self.first_height_row);
        self.heights.drain(..(keep - self.first_height_row) * n);
        self.first_height_row = keep;
        self.heights.extend(band.iter().map(|p| p[0]));
        self.next_row += rows;
        if let Some(above) = first.checked_sub(1) {
            let mut held = std::mem::take(&mut self.held);
            self.normal_row(above, &mut held);
            emit(&held)?;
            self.held = held;
        }
        let (done, last) = band.split_at_mut(rows.saturating_sub(1) * n);
        let this = &*self;
        done.par_chunks_mut(n)
            .enumerate()
            .for_each(|(row, pixels)| this.normal_row(first + row, pixels));
        emit(done)?;
        self.held.clear();
        self.held.extend_from_slice(last);
        Ok(())
    }

    /// Converts the image's last row, which has no row below, and passes it to `emit`.
    pub fn finish<E, F>(&mut self, emit: &mut F) -> Result<(), E>
    where
        F: FnMut(&[[f32; 4]]) -> Result<(), E> + ?Sized,
    {
        let Some(last) = self.next_row.checked_sub(1) else {
            return Ok(());
        };
        if self.held.is_empty() {
            return Ok(());
        }
        let mut held = std::mem::take(&mut self.held);
        self.normal_row(last, &mut held);
        emit(&held)
    }

    /// The heights of image row `row`, which must be among those kept.
    fn height_row(&self, row: usize) -> &[f32] {
        let start = (row - self.first_height_row) * self.size;
        &self.heights[start..start + self.size]
    }

    /// Tangent-space normals of image row `row` into `pixels` (its rendered outputs):
    /// central differences of the heights (one-sided at the image's edges, unless it is a
    /// tile), perturbed by
    /// each pixel's bump (lanes 1..4), encoded as 0.5 + 0.5·n. Slopes are clamped to ±1e18
    /// (steeper is vertical at any precision) and a perturbed normal too long to square is
    /// scaled down first, so any finite heights and bumps give a unit normal.
    fn normal_row(&self, row: usize, pixels: &mut [[f32; 4]]) {
        let n = self.size;
        let (dx, dz) = self.spacing;
        let center = self.height_row(row);
        let beyond = self.beyond.as_ref();
        let up = match (row.checked_sub(1), beyond) {
            (Some(above), _) => Some(self.height_row(above)),
            (None, beyond) => beyond.map(|(above, _)| above.as_slice()),
        };
        let down = match (row + 1 < self.next_row, beyond) {
            (true, _) => Some(self.height_row(row + 1)),
            (false, beyond) => beyond.map(|(_, below)| below.as_slice()),
        };
        let rows_apart = (usize::from(up.is_some()) + usize::from(down.is_some())).max(1) as f32;
        let (up, down) = (up.unwrap_or(center), down.unwrap_or(center));
        for (i, pixel) in pixels.iter_mut().enumerate() {
            let (left, right, columns_apart) = if beyond.is_some() {
                ((i + n - 1) % n, (i + 1) % n, 2)
            } else {
                let (left, right) = (i.saturating_sub(1), (i + 1).min(n - 1));
                (left, right, (right - left).max(1))
            };
            let steepest = 1.0e18;
            let slope_x = ((center[right] - center[left]) / (dx * columns_apart as f32))
                .clamp(-steepest, steepest);
            let slope_z = ((down[i] - up[i]) / (dz * rows_apart)).clamp(-steepest, steepest);
            // Object space (y up) with the bump added, as the preview lights it.
            let normal = glam::Vec3::new(-slope_x, 1.0, -slope_z).normalize()
                + glam::Vec3::new(pixel[1], pixel[2], pixel[3]);
            let normal = if normal.length_squared() > 1.0e38 {
                normal * 2f32.powi(-100)
            } else {
                normal
            };
            let normal = normal.normalize_or(glam::Vec3::Y);
            // Tangent space: x along +x (right), y towards the top of the image (-z), z up.
            let green = match self.convention {
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

/// One pixel of a map other than the normal map from the rendered outputs
/// ([`Map::channels`]) of a material shaded by `shading`.
fn pixel(map: Map, shading: Shading, p: [f32; 4]) -> [f32; 4] {
    let grey = |v: f32| [v, v, v, 1.0];
    // (metallic, roughness, occlusion, shininess) → the roughness the shading uses.
    let roughness = |p: [f32; 4]| {
        if shading == Shading::MetallicRoughness {
            p[1]
        } else {
            (2.0 / (p[3].max(0.0) + 2.0)).sqrt()
        }
    };
    match map {
        Map::Albedo | Map::Normal => p,
        Map::Alpha => grey(p[3]),
        Map::Height => grey(p[0]),
        Map::Specular | Map::Emission => [p[0], p[1], p[2], 1.0],
        Map::Roughness => grey(roughness(p)),
        Map::Metallic => grey(p[0]),
        Map::Occlusion => grey(p[2]),
        Map::Orm => [p[2], roughness(p), p[0], 1.0],
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
