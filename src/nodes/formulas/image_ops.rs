//! CPU twins of `shaders/image_ops.wgsl`, computed in f64 from f32 texels: blurs along a
//! line, slope blur, edges, curvature and occlusion from a height, the 2D transform of a
//! read and making a buffer tileable.

use super::buffers::Image;

/// The four lanes `a + (b - a) t`.
fn mix(a: [f64; 4], b: [f64; 4], t: f64) -> [f64; 4] {
    [0, 1, 2, 3].map(|k| a[k] + (b[k] - a[k]) * t)
}

/// Hermite step from 0 at `edge0` to 1 at `edge1` (as WGSL's `smoothstep`).
fn smoothstep(edge0: f64, edge1: f64, x: f64) -> f64 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl Image {
    /// The mean of `samples` bilinear reads along the segment `uv ± reach` (as
    /// `veneer_line_blur`).
    pub fn line_blur(&self, uv: [f64; 2], reach: [f64; 2], samples: u32) -> [f64; 4] {
        let n = samples.max(1);
        if n == 1 {
            return self.bilinear(uv);
        }
        let mut sum = [0.0; 4];
        for k in 0..n {
            let along = 2.0 * f64::from(k) / f64::from(n - 1) - 1.0;
            let read = self.bilinear([uv[0] + along * reach[0], uv[1] + along * reach[1]]);
            for lane in 0..4 {
                sum[lane] += read[lane];
            }
        }
        sum.map(|lane| lane / f64::from(n))
    }

    /// A blur `length` long through `uv` at `angle` degrees (as
    /// `veneer_directional_blur`).
    pub fn directional_blur(
        &self,
        uv: [f64; 2],
        angle: f64,
        length: f64,
        samples: u32,
    ) -> [f64; 4] {
        let radians = angle * 0.017453292;
        let half = 0.5 * length.clamp(0.0, 1.0);
        self.line_blur(uv, [half * radians.cos(), half * radians.sin()], samples)
    }

    /// The gradient of the first lane per domain unit (as `veneer_buffer_gradient`).
    pub fn gradient(&self, uv: [f64; 2]) -> [f64; 2] {
        let size = [f64::from(self.width), f64::from(self.height)];
        let read = |du: f64, dv: f64| self.bilinear([uv[0] + du, uv[1] + dv])[0];
        let (dx, dy) = (1.0 / size[0], 1.0 / size[1]);
        [
            (read(dx, 0.0) - read(-dx, 0.0)) * size[0] * 0.5,
            (read(0.0, dy) - read(0.0, -dy)) * size[1] * 0.5,
        ]
    }

    /// This image blurred along the slope of `slope` (as `veneer_slope_blur`).
    pub fn slope_blur(
        &self,
        slope: &Image,
        uv: [f64; 2],
        intensity: f64,
        samples: u32,
    ) -> [f64; 4] {
        let gradient = slope.gradient(uv);
        let reach = gradient.map(|g| (-0.5 * intensity * g).clamp(-0.25, 0.25));
        self.line_blur([uv[0] + reach[0], uv[1] + reach[1]], reach, samples)
    }

    /// This image read moved downhill along the slope of `slope` (as
    /// `veneer_slope_warp`).
    pub fn slope_warp(&self, slope: &Image, uv: [f64; 2], amount: f64) -> [f64; 4] {
        let gradient = slope.gradient(uv);
        let reach = gradient.map(|g| (-amount * g).clamp(-0.25, 0.25));
        self.bilinear([uv[0] + reach[0], uv[1] + reach[1]])
    }

    /// The clamped Sobel gradient length of the first lane (as `veneer_edge_detect`).
    pub fn edge_detect(&self, uv: [f64; 2], width: f64, strength: f64) -> f64 {
        let d = [
            width.max(0.0) / f64::from(self.width),
            width.max(0.0) / f64::from(self.height),
        ];
        let h = |i: i32, j: i32| {
            self.bilinear([uv[0] + f64::from(i) * d[0], uv[1] + f64::from(j) * d[1]])[0]
        };
        let gx = (h(1, -1) + 2.0 * h(1, 0) + h(1, 1) - h(-1, -1) - 2.0 * h(-1, 0) - h(-1, 1)) / 8.0;
        let gy = (h(-1, 1) + 2.0 * h(0, 1) + h(1, 1) - h(-1, -1) - 2.0 * h(0, -1) - h(1, -1)) / 8.0;
        (strength * (gx * gx + gy * gy).sqrt()).clamp(0.0, 1.0)
    }

    /// The curvature of the height, 0.5 where flat (as `veneer_curvature`).
    pub fn curvature(&self, uv: [f64; 2], radius: f64, strength: f64) -> f64 {
        let r = radius.max(0.0);
        let h = |du: f64, dv: f64| self.bilinear([uv[0] + du, uv[1] + dv])[0];
        let around = h(r, 0.0) + h(-r, 0.0) + h(0.0, r) + h(0.0, -r);
        (0.5 + strength * (4.0 * h(0.0, 0.0) - around)).clamp(0.0, 1.0)
    }

    /// Horizon-based occlusion of the height (as `veneer_height_occlusion`).
    pub fn height_occlusion(
        &self,
        uv: [f64; 2],
        radius: f64,
        depth: f64,
        directions: u32,
        steps: u32,
    ) -> f64 {
        let h0 = self.bilinear(uv)[0] * depth;
        let r = radius.max(1e-6);
        let (n, m) = (directions.max(1), steps.max(1));
        let mut occluded = 0.0;
        for k in 0..n {
            let angle = 6.2831855 * f64::from(k) / f64::from(n);
            let direction = [angle.cos(), angle.sin()];
            let mut rise: f64 = 0.0;
            for j in 1..=m {
                let distance = r * f64::from(j) / f64::from(m);
                let at = [
                    uv[0] + distance * direction[0],
                    uv[1] + distance * direction[1],
                ];
                let h = self.bilinear(at)[0] * depth;
                rise = rise.max((h - h0) / distance);
            }
            occluded += rise / (1.0 + rise * rise).sqrt();
        }
        1.0 - occluded / f64::from(n)
    }

    /// This image made tileable within `width` of each edge (as
    /// `veneer_make_tileable`).
    pub fn make_tileable(&self, uv: [f64; 2], width: f64) -> [f64; 4] {
        let p = uv.map(|u| u - u.floor());
        let w = width.clamp(1e-4, 0.5);
        let fade = p.map(|p| 1.0 - smoothstep(0.0, w, p.min(1.0 - p)));
        let moved = p.map(|p| p + 0.5 - (p + 0.5).floor());
        let a = self.bilinear(p);
        let bu = self.bilinear([moved[0], p[1]]);
        let bv = self.bilinear([p[0], moved[1]]);
        let buv = self.bilinear(moved);
        mix(mix(a, bu, fade[0]), mix(bv, buv, fade[0]), fade[1])
    }
}

/// The domain coordinate a directional warp reads at (as
/// `veneer_directional_warp_uv`).
pub fn directional_warp_uv(uv: [f64; 2], intensity: f64, angle: f64, amount: f64) -> [f64; 2] {
    let radians = angle * 0.017453292;
    let reach = (amount * intensity).clamp(-1e6, 1e6);
    [uv[0] + reach * radians.cos(), uv[1] + reach * radians.sin()]
}

/// The domain coordinate a 2D transform reads at for `uv` (as
/// `veneer_transform_2d_uv`), from f32 inputs as the GPU has them.
pub fn transform_2d_uv(uv: [f64; 2], offset: [f64; 2], angle: f64, scale: [f64; 2]) -> [f64; 2] {
    let radians = -angle * 0.017453292;
    let (s, c) = radians.sin_cos();
    let safe = scale.map(|k| if k.abs() < 1e-30 { 1e30 } else { k });
    let finite = |v: f64| v.clamp(-f64::from(f32::MAX), f64::from(f32::MAX));
    let p = [
        finite(uv[0] - 0.5 - offset[0]) / safe[0],
        finite(uv[1] - 0.5 - offset[1]) / safe[1],
    ];
    [c * p[0] - s * p[1] + 0.5, s * p[0] + c * p[1] + 0.5]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nodes::passes::EdgeMode;

    /// A non-repeating ramp along u, `n` texels square.
    fn ramp(n: u32) -> Image {
        let texels = (0..n * n)
            .map(|k| [(k % n) as f32 / n as f32, 0.0, 0.0, 1.0])
            .collect();
        Image {
            width: n,
            height: n,
            edge: EdgeMode::Wrap,
            texels,
        }
    }

    #[test]
    fn a_tileable_ramp_continues_across_its_edges_and_keeps_its_middle() {
        let image = ramp(32);
        for v in [0.1, 0.5, 0.9] {
            let left = image.make_tileable([0.0, v], 0.2)[0];
            let right = image.make_tileable([1.0 - 1e-9, v], 0.2)[0];
            assert!((left - right).abs() < 1e-6, "{left} against {right}");
            let across = image.make_tileable([v, 0.0], 0.2)[0];
            let back = image.make_tileable([v, 1.0 - 1e-9], 0.2)[0];
            assert!((across - back).abs() < 1e-6);
        }
        let middle = [0.5 + 0.5 / 32.0, 0.5 + 0.5 / 32.0];
        assert_eq!(image.make_tileable(middle, 0.2), image.bilinear(middle));
    }

    #[test]
    fn flat_heights_are_unoccluded_and_uncurved_and_a_pit_is_occluded() {
        let mut image = ramp(16);
        image
            .texels
            .iter_mut()
            .for_each(|t| *t = [0.5, 0.0, 0.0, 1.0]);
        let at = [0.5 + 0.5 / 16.0; 2];
        assert_eq!(image.height_occlusion(at, 0.2, 1.0, 8, 8), 1.0);
        assert_eq!(image.curvature(at, 0.1, 4.0), 0.5);
        assert_eq!(image.edge_detect(at, 1.0, 4.0), 0.0);
        image.texels[8 * 16 + 8] = [0.0, 0.0, 0.0, 1.0];
        assert!(image.height_occlusion(at, 0.2, 1.0, 8, 8) < 1.0);
        assert!(image.curvature(at, 1.0 / 16.0, 4.0) < 0.5);
    }

    #[test]
    fn a_zero_scale_reads_the_centre_and_a_turn_by_360_degrees_reads_in_place() {
        assert_eq!(
            transform_2d_uv([0.2, 0.9], [0.0; 2], 0.0, [0.0, 0.0]),
            [0.5, 0.5]
        );
        let turned = transform_2d_uv([0.2, 0.9], [0.0; 2], 360.0, [1.0, 1.0]);
        assert!((turned[0] - 0.2).abs() < 1e-6 && (turned[1] - 0.9).abs() < 1e-6);
    }
}
