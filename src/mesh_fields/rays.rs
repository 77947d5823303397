//! The ray directions mesh fields cast: low-discrepancy (Halton, bases 2 and 3) points
//! over a hemisphere or a cone about a direction, shifted by a per-vertex random offset
//! (Cranley–Patterson rotation) so neighbouring vertices do not share their error
//! pattern; the same directions for the same vertex on every run. Every prefix of the
//! sequence is evenly spread, so sampling may stop early.

use glam::Vec3A;

/// The PCG hash of `value` (one round of the permuted congruential generator).
fn pcg(value: u32) -> u32 {
    let state = value.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// A number in [0, 1) from the top 24 bits of a hash.
fn unit(hash: u32) -> f32 {
    (hash >> 8) as f32 / (1u32 << 24) as f32
}

/// The radical inverse of `k` in `base`: its digits mirrored about the point.
fn radical_inverse(mut k: u32, base: u32) -> f32 {
    let (mut inverse, mut scale) = (0.0f64, 1.0f64);
    while k > 0 {
        scale /= f64::from(base);
        inverse += f64::from(k % base) * scale;
        k /= base;
    }
    inverse as f32
}

/// The `k`-th point of the Halton sequence in [0, 1)², shifted by `offset` (wrapped).
fn halton(k: u32, offset: [f32; 2]) -> [f32; 2] {
    let [first, second] = [radical_inverse(k, 2), radical_inverse(k, 3)];
    [(first + offset[0]).fract(), (second + offset[1]).fract()]
}

/// Two unit vectors completing `normal` to a right-handed orthonormal basis (Duff et
/// al. 2017, no branch on the normal's direction other than its sign).
fn basis(normal: Vec3A) -> (Vec3A, Vec3A) {
    let sign = 1.0f32.copysign(normal.z);
    let a = -1.0 / (sign + normal.z);
    let b = normal.x * normal.y * a;
    (
        Vec3A::new(
            1.0 + sign * normal.x * normal.x * a,
            sign * b,
            -sign * normal.x,
        ),
        Vec3A::new(b, sign + normal.y * normal.y * a, -normal.y),
    )
}

/// The random offset of vertex `vertex`'s points.
fn offset(vertex: u32) -> [f32; 2] {
    let first = pcg(vertex ^ 0x5bd1_e995);
    [unit(first), unit(pcg(first))]
}

/// Directions over the hemisphere about the unit `normal`, distributed as the cosine
/// (so the mean of their visibility is the cosine-weighted visibility); as many as taken.
pub fn cosine_hemisphere(normal: Vec3A, vertex: u32) -> impl Iterator<Item = Vec3A> {
    let (tangent, bitangent) = basis(normal);
    let shift = offset(vertex);
    (0..).map(move |k| {
        let [u, v] = halton(k, shift);
        let (radius, angle) = (u.sqrt(), std::f32::consts::TAU * v);
        let up = (1.0 - u).max(0.0).sqrt();
        (tangent * (radius * angle.cos()) + bitangent * (radius * angle.sin()) + normal * up)
            .normalize_or(normal)
    })
}

/// Directions spread evenly over the solid angle of a cone of half-angle `half_angle`
/// (radians) about the unit `axis`; as many as taken.
pub fn cone(axis: Vec3A, half_angle: f32, vertex: u32) -> impl Iterator<Item = Vec3A> {
    let (tangent, bitangent) = basis(axis);
    let shift = offset(vertex);
    let lowest = half_angle.cos();
    (0..).map(move |k| {
        let [u, v] = halton(k, shift);
        let cos = 1.0 - u * (1.0 - lowest);
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let angle = std::f32::consts::TAU * v;
        (tangent * (sin * angle.cos()) + bitangent * (sin * angle.sin()) + axis * cos)
            .normalize_or(axis)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hemisphere_directions_are_cosine_distributed_about_the_normal() {
        let normal = Vec3A::new(0.3, -0.8, 0.52).normalize();
        let directions: Vec<Vec3A> = cosine_hemisphere(normal, 17).take(4096).collect();
        assert!(directions.iter().all(|d| d.dot(normal) >= 0.0));
        assert!(directions.iter().all(|d| (d.length() - 1.0).abs() < 1e-5));
        // The mean cosine of a cosine-distributed hemisphere is 2/3.
        let mean: f32 = directions.iter().map(|d| d.dot(normal)).sum::<f32>() / 4096.0;
        assert!((mean - 2.0 / 3.0).abs() < 1e-3, "{mean}");
    }

    #[test]
    fn cone_directions_stay_within_the_cone_and_differ_between_vertices() {
        let axis = Vec3A::new(0.0, 0.0, -1.0);
        let half_angle = 0.5f32;
        let first: Vec<Vec3A> = cone(axis, half_angle, 1).take(64).collect();
        assert!(first.iter().all(|d| d.dot(axis) >= half_angle.cos() - 1e-6));
        let second: Vec<Vec3A> = cone(axis, half_angle, 2).take(64).collect();
        assert_ne!(first, second);
        assert_eq!(
            first,
            cone(axis, half_angle, 1).take(64).collect::<Vec<_>>()
        );
    }
}
