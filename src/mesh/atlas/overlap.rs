//! Whether a mesh's UV layout gives every point of its surface texels of its own. A
//! layout whose triangles overlap in texture space (a cube whose faces each span the
//! unit square, mirrored halves) or reach past the unit square cannot hold a buffer
//! rendered over the surface: such a mesh gets an atlas for it.

use super::Mesh;

/// The side of the grid of texel centres on which overlaps are counted.
const GRID: usize = 256;

/// The share of the covered texel centres covered more than once past which a layout
/// overlaps.
const OVERLAP_SHARE: f64 = 0.01;

/// How far inside a triangle (in texels², as the edge function measures) a texel
/// centre must lie to count: a centre on the edge two triangles share counts for
/// neither, not for both.
const INSIDE: f64 = 1e-9;

/// How far past the unit square a texture coordinate may lie and still count as in it.
const SQUARE_SLACK: f32 = 1e-4;

impl Mesh {
    /// The share of the texel centres of a 256² grid over the unit square inside the UV
    /// layout's triangles that lie inside more than one (0 for a layout without
    /// overlaps).
    pub fn uv_overlap(&self) -> f64 {
        let mut counts = vec![0u8; GRID * GRID];
        for triangle in self.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| {
                let uv = self.uvs[triangle[k] as usize];
                glam::DVec2::new(f64::from(uv[0]), f64::from(uv[1])) * GRID as f64
            });
            let area = (b - a).perp_dot(c - a);
            if !area.is_finite() || area == 0.0 {
                continue;
            }
            let low = a.min(b).min(c).floor().max(glam::DVec2::ZERO);
            let high = a.max(b).max(c).ceil().min(glam::DVec2::splat(GRID as f64));
            for y in low.y as usize..high.y as usize {
                for x in low.x as usize..high.x as usize {
                    let p = glam::DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
                    let inside = [(a, b), (b, c), (c, a)].iter().all(|(from, to)| {
                        (*to - *from).perp_dot(p - *from) * area.signum() > INSIDE
                    });
                    if inside {
                        let count = &mut counts[y * GRID + x];
                        *count = count.saturating_add(1);
                    }
                }
            }
        }
        let covered = counts.iter().filter(|&&count| count > 0).count();
        let twice = counts.iter().filter(|&&count| count > 1).count();
        if covered == 0 {
            0.0
        } else {
            twice as f64 / covered as f64
        }
    }

    /// Whether the UV layout gives each point of the surface texels of its own: it
    /// covers some area, stays within the unit square and does not overlap itself.
    pub fn has_own_texels(&self) -> bool {
        let in_square = |uv: &[f32; 2]| {
            uv.iter()
                .all(|&t| (-SQUARE_SLACK..=1.0 + SQUARE_SLACK).contains(&t))
        };
        self.has_uv_layout() && self.uvs.iter().all(in_square) && self.uv_overlap() <= OVERLAP_SHARE
    }

    /// This mesh when its UV layout gives each point texels of its own, else the mesh
    /// with an automatic atlas for textures of `texture_size`² texels.
    pub fn with_own_texels(self, texture_size: u32) -> Mesh {
        if self.has_own_texels() {
            self
        } else {
            self.with_uv_atlas(texture_size)
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_cube_overlaps_and_its_atlas_does_not() {
        let cube = crate::mesh::primitive("cube").expect("a cube");
        assert!(cube.uv_overlap() > 0.8, "six faces over one square");
        assert!(!cube.has_own_texels());
        let atlas = cube.with_own_texels(256);
        assert!(atlas.has_own_texels(), "{}", atlas.uv_overlap());
        for name in ["sphere", "torus", "plane"] {
            let mesh = crate::mesh::primitive(name).expect("a primitive");
            assert!(mesh.has_own_texels(), "{name}: {}", mesh.uv_overlap());
        }
    }

    #[test]
    fn a_layout_past_the_unit_square_is_not_its_own() {
        let mut plane = crate::mesh::primitive("plane").expect("a plane");
        for uv in &mut plane.uvs {
            uv[0] *= 2.0;
        }
        assert_eq!(plane.uv_overlap(), 0.0);
        assert!(!plane.has_own_texels());
    }
}
