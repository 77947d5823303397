//! Whether a bitmap's opposite edges continue each other, for a tile that wraps it:
//! a bitmap cannot be evaluated past its edge, so the jump across its wrap is measured
//! against the jumps between neighbouring texels inside it.

use super::Bitmap;

impl Bitmap {
    /// How much larger the jump across the wrap is than a jump between neighbouring
    /// texels inside, on average over the colour lanes: left/right (the last column
    /// against the first) and top/bottom. About 1 for a bitmap that tiles (its wrap is
    /// one more pair of neighbours), larger for a photo's seam; 1 for a flat bitmap.
    pub fn edge_ratios(&self) -> [f32; 2] {
        let (width, height) = (self.width as usize, self.height as usize);
        let texel = |x: usize, y: usize| &self.texels[y * width + x];
        let jump = |a: &[f32; 4], b: &[f32; 4]| -> f64 {
            (0..3).map(|k| f64::from((a[k] - b[k]).abs())).sum()
        };
        let ratio = |wrap: f64, wraps: usize, inside: f64, insides: usize| -> f32 {
            let (wrap, inside) = (wrap / wraps.max(1) as f64, inside / insides.max(1) as f64);
            if inside <= f64::EPSILON {
                if wrap <= f64::EPSILON {
                    1.0
                } else {
                    f32::INFINITY
                }
            } else {
                (wrap / inside) as f32
            }
        };
        let (mut across, mut down) = (0.0, 0.0);
        for y in 0..height {
            for x in 0..width.saturating_sub(1) {
                across += jump(texel(x, y), texel(x + 1, y));
            }
        }
        for y in 0..height.saturating_sub(1) {
            for x in 0..width {
                down += jump(texel(x, y), texel(x, y + 1));
            }
        }
        let left_right: f64 = (0..height)
            .map(|y| jump(texel(width - 1, y), texel(0, y)))
            .sum();
        let top_bottom: f64 = (0..width)
            .map(|x| jump(texel(x, height - 1), texel(x, 0)))
            .sum();
        [
            ratio(left_right, height, across, (width - 1) * height),
            ratio(top_bottom, width, down, width * (height - 1)),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::Bitmap;

    /// A width×height bitmap of `value(x, y)` in every colour lane.
    fn bitmap(width: u32, height: u32, value: impl Fn(f32, f32) -> f32) -> Bitmap {
        let texels = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| {
                let v = value(x as f32 / width as f32, y as f32 / height as f32);
                [v, v, v, 1.0]
            })
            .collect();
        Bitmap {
            width,
            height,
            texels,
            from_srgb: false,
            lanes: [[0.0, 1.0]; 4],
        }
    }

    #[test]
    fn a_repeating_bitmap_scores_one_a_ramp_its_seam_and_a_flat_one_one() {
        let tau = std::f32::consts::TAU;
        // Waves running every way, whole numbers of them across: the wrap is one more
        // pair of neighbours.
        let waves = bitmap(96, 96, |u, v| {
            [
                (1.0, 3.0, 0.3),
                (4.0, -2.0, 1.9),
                (-5.0, 1.0, 4.0),
                (2.0, 5.0, 2.6),
            ]
            .iter()
            .map(|(a, b, phase)| (tau * (a * u + b * v) + phase).sin())
            .sum()
        });
        for ratio in waves.edge_ratios() {
            assert!((ratio - 1.0).abs() < 0.2, "{ratio}");
        }
        // A ramp across: every step 1/64 inside, the whole ramp back across the wrap;
        // nothing changes down, so nothing jumps there either.
        let ramp = bitmap(64, 8, |u, _| u);
        let [left_right, top_bottom] = ramp.edge_ratios();
        assert!((left_right - 63.0).abs() < 1e-3, "{left_right}");
        assert_eq!(top_bottom, 1.0);
        assert_eq!(bitmap(4, 4, |_, _| 0.5).edge_ratios(), [1.0, 1.0]);
        // Half dark, half light: the wrap jumps as the middle does, once where the 7
        // pairs inside jump once between them.
        let halves = bitmap(8, 8, |u, _| if u < 0.5 { 0.0 } else { 1.0 });
        assert!((halves.edge_ratios()[0] - 7.0).abs() < 1e-4);
    }
}
