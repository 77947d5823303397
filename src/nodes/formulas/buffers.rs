//! CPU twins of `shaders/buffers.wgsl`: a buffer as an image of four f32 lanes per
//! texel, read at texels under an edge mode and between them (bilinear, bicubic), the
//! Gaussian blur's axis pass and the Sobel normal. Computed in f64 from f32 texels: the
//! reference the GPU's passes are measured against.

use super::real::{Real, V3, safe_normalize};
use crate::nodes::passes::EdgeMode;

/// A buffer on the CPU: `width × height` texels, rows from the top, each four lanes.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    /// What reads beyond the edges see.
    pub edge: EdgeMode,
    pub texels: Vec<[f32; 4]>,
}

/// Index `i` of an axis of `n` texels under `edge` (as `veneer_edge_index`).
pub fn edge_index(i: i64, n: i64, edge: EdgeMode) -> i64 {
    match edge {
        EdgeMode::Clamp => i.clamp(0, n - 1),
        EdgeMode::Mirror => {
            let m = i.rem_euclid(2 * n);
            if m >= n { 2 * n - 1 - m } else { m }
        }
        EdgeMode::Wrap => i.rem_euclid(n),
    }
}

impl Image {
    /// A file's pixels read past its edges by `edge`.
    pub fn of_bitmap(bitmap: &crate::bitmaps::Bitmap, edge: EdgeMode) -> Image {
        Image {
            width: bitmap.width,
            height: bitmap.height,
            edge,
            texels: bitmap.texels.clone(),
        }
    }

    /// Texel (x, y), beyond the edges by the image's edge mode.
    pub fn texel(&self, x: i64, y: i64) -> [f64; 4] {
        let x = edge_index(x, i64::from(self.width), self.edge);
        let y = edge_index(y, i64::from(self.height), self.edge);
        self.texels[(y * i64::from(self.width) + x) as usize].map(f64::from)
    }

    /// The place of domain coordinate `uv` among the texel centres (as
    /// `veneer_buffer_place`), scaled to texels in f32 as the GPU scales it: the
    /// fractions that weigh neighbouring texels are then the GPU's, which matters where
    /// a node's output is steep in them (a round bevel at its foot).
    pub(crate) fn place(&self, uv: [f64; 2]) -> [f64; 2] {
        let size = [self.width as f32, self.height as f32];
        [0, 1].map(|k| {
            let u = uv[k];
            let near = match self.edge {
                EdgeMode::Wrap => u - u.floor(),
                EdgeMode::Clamp => u.clamp(-1.0, 2.0),
                EdgeMode::Mirror => u - 2.0 * (u * 0.5).floor(),
            };
            f64::from(near as f32 * size[k] - 0.5)
        })
    }

    /// The image at `uv`, bilinear between texel centres (as `veneer_buffer_bilinear`).
    pub fn bilinear(&self, uv: [f64; 2]) -> [f64; 4] {
        let place = self.place(uv);
        let base = place.map(f64::floor);
        let f = [place[0] - base[0], place[1] - base[1]];
        let (x, y) = (base[0] as i64, base[1] as i64);
        let mix = |a: [f64; 4], b: [f64; 4], t: f64| [0, 1, 2, 3].map(|k| a[k] + (b[k] - a[k]) * t);
        let top = mix(self.texel(x, y), self.texel(x + 1, y), f[0]);
        let bottom = mix(self.texel(x, y + 1), self.texel(x + 1, y + 1), f[0]);
        mix(top, bottom, f[1])
    }

    /// The image at `uv`, Catmull-Rom bicubic over 4×4 texels (as
    /// `veneer_buffer_bicubic`).
    pub fn bicubic(&self, uv: [f64; 2]) -> [f64; 4] {
        let place = self.place(uv);
        let base = place.map(f64::floor);
        let wx = catmull_rom(place[0] - base[0]);
        let wy = catmull_rom(place[1] - base[1]);
        let (x0, y0) = (base[0] as i64 - 1, base[1] as i64 - 1);
        let mut sum = [0.0; 4];
        for (y, wy) in wy.iter().enumerate() {
            for (x, wx) in wx.iter().enumerate() {
                let texel = self.texel(x0 + x as i64, y0 + y as i64);
                for k in 0..4 {
                    sum[k] += wy * wx * texel[k];
                }
            }
        }
        sum
    }

    /// One axis of the Gaussian blur at texel (x, y) (as `veneer_blur_axis`).
    pub fn blur_axis(&self, texel: [i64; 2], axis: [i64; 2], radius: f64) -> [f64; 4] {
        let sigma = radius.max(1e-3) / 3.0;
        let reach = radius.clamp(0.0, 1024.0).ceil() as i64;
        let mut sum = self.texel(texel[0], texel[1]);
        let mut weight = 1.0;
        for k in 1..=reach {
            let w = (-0.5 * (k * k) as f64 / (sigma * sigma)).exp();
            let ahead = self.texel(texel[0] + k * axis[0], texel[1] + k * axis[1]);
            let behind = self.texel(texel[0] - k * axis[0], texel[1] - k * axis[1]);
            for lane in 0..4 {
                sum[lane] += w * (ahead[lane] + behind[lane]);
            }
            weight += 2.0 * w;
        }
        sum.map(|lane| lane / weight)
    }

    /// The tangent-space normal of the height (first lane) at `uv` by Sobel differences
    /// (as `veneer_height_normal`).
    pub fn height_normal<R: Real>(&self, uv: [f64; 2], strength: f64, y_sign: f64) -> V3<R> {
        let size = [f64::from(self.width), f64::from(self.height)];
        let h = |i: i32, j: i32| {
            let at = [
                uv[0] + f64::from(i) / size[0],
                uv[1] + f64::from(j) / size[1],
            ];
            self.bilinear(at)[0]
        };
        let du = (h(1, -1) + 2.0 * h(1, 0) + h(1, 1) - h(-1, -1) - 2.0 * h(-1, 0) - h(-1, 1))
            * size[0]
            / 8.0;
        let dv = (h(-1, 1) + 2.0 * h(0, 1) + h(1, 1) - h(-1, -1) - 2.0 * h(0, -1) - h(1, -1))
            * size[1]
            / 8.0;
        let normal = [-strength * du, y_sign * strength * dv, 1.0].map(R::c);
        safe_normalize(normal, 3)
    }

    /// The image with every texel replaced by `texel(image, [x, y])`.
    pub fn map_texels(&self, texel: impl Fn(&Image, [i64; 2]) -> [f64; 4] + Sync) -> Image {
        use rayon::prelude::*;
        let width = self.width as usize;
        let texels = (0..self.texels.len())
            .into_par_iter()
            .map(|k| {
                let at = [(k % width) as i64, (k / width) as i64];
                texel(self, at).map(|lane| lane as f32)
            })
            .collect();
        Image {
            texels,
            ..self.clone()
        }
    }
}

/// The Catmull-Rom weights of the four texels around place `f` past the second (as
/// `veneer_catmull_rom`).
fn catmull_rom(f: f64) -> [f64; 4] {
    let (f2, f3) = (f * f, f * f * f);
    [
        -0.5 * f3 + f2 - 0.5 * f,
        1.5 * f3 - 2.5 * f2 + 1.0,
        -1.5 * f3 + 2.0 * f2 + 0.5 * f,
        0.5 * f3 - 0.5 * f2,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp(edge: EdgeMode) -> Image {
        Image {
            width: 4,
            height: 2,
            edge,
            texels: (0..8).map(|k| [k as f32, 0.0, 0.0, 1.0]).collect(),
        }
    }

    #[test]
    fn edge_modes_reach_past_the_edges() {
        let wrapped: Vec<i64> = (-2..6).map(|i| edge_index(i, 4, EdgeMode::Wrap)).collect();
        assert_eq!(wrapped, [2, 3, 0, 1, 2, 3, 0, 1]);
        let clamped: Vec<i64> = (-2..6).map(|i| edge_index(i, 4, EdgeMode::Clamp)).collect();
        assert_eq!(clamped, [0, 0, 0, 1, 2, 3, 3, 3]);
        let mirrored: Vec<i64> = (-2..6)
            .map(|i| edge_index(i, 4, EdgeMode::Mirror))
            .collect();
        assert_eq!(mirrored, [1, 0, 0, 1, 2, 3, 3, 2]);
    }

    #[test]
    fn texel_centres_read_exactly_and_huge_coordinates_stay_finite() {
        let image = ramp(EdgeMode::Wrap);
        assert_eq!(image.bilinear([2.5 / 4.0, 0.25])[0], 2.0);
        assert_eq!(image.bicubic([2.5 / 4.0, 0.25])[0], 2.0);
        // Halfway between the last texel and the first, across the wrap.
        assert_eq!(image.bilinear([1.0, 0.25])[0], 1.5);
        for uv in [[1e30, -1e30], [f64::MAX, 3.0]] {
            assert!(image.bilinear(uv).iter().all(|v| v.is_finite()));
        }
    }

    #[test]
    fn blur_keeps_a_constant_and_spreads_a_spike_symmetrically() {
        let mut image = ramp(EdgeMode::Clamp);
        image.texels.iter_mut().for_each(|t| *t = [0.5; 4]);
        assert!((image.blur_axis([1, 1], [1, 0], 6.0)[0] - 0.5).abs() < 1e-12);
        image.texels[1] = [1.0; 4];
        image.edge = EdgeMode::Wrap;
        let left = image.blur_axis([0, 0], [1, 0], 2.0)[0];
        let right = image.blur_axis([2, 0], [1, 0], 2.0)[0];
        assert!((left - right).abs() < 1e-12 && left > 0.5);
    }
}
