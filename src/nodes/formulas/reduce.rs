//! CPU twins of `shaders/reduce.wgsl`: the minimum, maximum and sum of a buffer's first
//! lane, reduced in passes over the buffer, step by step as the GPU runs them. A
//! texel's state is (its own value, then the minimum, maximum and sum over a window
//! starting at it): row steps double the windows along the rows (step k adds the window
//! 2ᵏ texels on, where it lies within the row), so the first texel of each row ends
//! with the row's; column steps then do the same with those row totals down the first
//! column, and texel (0, 0) ends with the whole buffer's. Pairwise sums: the sum's
//! rounding error grows with the logarithm of the texel count, not the count.

use super::buffers::Image;

/// Steps along an axis: windows of 2, 4, … texels, up to the largest buffer side
/// ([`crate::nodes::passes::MAX_BUFFER_SIZE`], 2¹³).
pub const REDUCE_STEPS: u32 = 13;

/// The seed state of `texel` (as `veneer_reduce_seed`): its value, and its value as the
/// minimum, maximum and sum of a one-texel window.
pub fn reduce_seed(image: &Image, texel: [i64; 2]) -> [f64; 4] {
    let value = image.texel(texel[0], texel[1])[0];
    [value; 4]
}

/// The window totals (minimum, maximum, sum) of `a` and `b` together, in f32.
fn combine(a: [f64; 4], b: [f64; 4]) -> [f64; 3] {
    [
        a[1].min(b[1]),
        a[2].max(b[2]),
        f64::from(a[3] as f32 + b[3] as f32),
    ]
}

/// Reduction step `k` along `axis` (0: rows, 1: columns) at `texel` (as
/// `veneer_reduce_step`). Column step 0 starts from the row totals of the first column.
pub fn reduce_step(image: &Image, texel: [i64; 2], axis: usize, k: u32) -> [f64; 4] {
    let size = [i64::from(image.width), i64::from(image.height)];
    let here = image.texel(texel[0], texel[1]);
    let s = 1_i64 << k;
    let mut window = texel;
    if axis == 1 && k == 0 {
        window[0] = 0;
    }
    let mut state = image.texel(window[0], window[1]);
    state[0] = here[0];
    let mut next = window;
    next[axis] += s;
    if next[axis] < size[axis] {
        let [min, max, sum] = combine(state, image.texel(next[0], next[1]));
        state = [here[0], min, max, sum];
    }
    state
}

/// The minimum, maximum and mean of a reduced buffer's values (as `veneer_reduced`).
pub fn reduced(image: &Image) -> [f64; 3] {
    let total = image.texel(0, 0);
    let count = f64::from(image.width) * f64::from(image.height);
    [total[1], total[2], f64::from((total[3] / count) as f32)]
}

/// The reduced image of `image` after every stage: the seeds, the row steps, the column
/// steps.
pub fn reduce(image: &Image) -> Image {
    let mut reduced = image.map_texels(reduce_seed);
    for axis in 0..2 {
        for k in 0..REDUCE_STEPS {
            reduced = reduced.map_texels(|image, texel| reduce_step(image, texel, axis, k));
        }
    }
    reduced
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nodes::passes::EdgeMode;

    #[test]
    fn a_reduced_buffer_of_any_size_holds_its_minimum_maximum_and_mean() {
        for (width, height) in [(1, 1), (5, 3), (16, 16), (37, 11)] {
            let values: Vec<f32> = (0..width * height)
                .map(|k| ((k * 7919) % 101) as f32 / 10.0 - 3.0)
                .collect();
            let image = Image {
                width,
                height,
                edge: EdgeMode::Wrap,
                texels: values.iter().map(|&v| [v, 0.0, 0.0, 1.0]).collect(),
            };
            let [min, max, mean] = reduced(&reduce(&image));
            let exact = |f: fn(f64, f64) -> f64| values.iter().map(|&v| f64::from(v)).reduce(f);
            assert_eq!(min, exact(f64::min).unwrap());
            assert_eq!(max, exact(f64::max).unwrap());
            let sum: f64 = values.iter().map(|&v| f64::from(v)).sum();
            let exact_mean = sum / f64::from(width * height);
            assert!(
                (mean - exact_mean).abs() < 1e-5,
                "{mean} against {exact_mean}"
            );
        }
    }
}
