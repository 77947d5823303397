//! The robust variant's preparation of a poor mesh (Sharp & Crane 2020): intrinsic
//! mollification lengthens every edge by the same small amount so that each triangle
//! satisfies the triangle inequality with a margin, then intrinsic edge flips make the
//! triangulation Delaunay, so every cotangent weight is non-negative. The vertices stay
//! the same, so fields computed on the result belong to the original vertices.

use super::triangulation::{NO_TWIN, Triangulation, area_from_lengths, half_edge, split};

impl Triangulation {
    /// Adds `ε` to every edge length, the smallest amount that makes `a + b − c ≥ δ` in
    /// every triangle, with `δ = relative · mean edge length`. Returns `ε`.
    pub fn mollify(&mut self, relative: f64) -> f64 {
        let delta = relative * self.mean_edge_length();
        let epsilon = self
            .lengths
            .iter()
            .flat_map(|l| (0..3).map(move |k| delta - (l[(k + 1) % 3] + l[(k + 2) % 3] - l[k])))
            .fold(0.0f64, f64::max);
        for length in self.lengths.iter_mut().flatten() {
            *length += epsilon;
        }
        epsilon
    }

    /// Flips edges until every interior edge is Delaunay (the two angles across it sum
    /// to at most π), returning the number of flips.
    pub fn flip_to_delaunay(&mut self) -> usize {
        let all = (0..self.twins.len() as u32).collect();
        self.flip_from(all)
    }

    /// Flips the edges of `suspects` that are not Delaunay, and then those each flip
    /// leaves not Delaunay, until none is; the rest of the triangulation must be Delaunay
    /// already. Returns the number of flips.
    pub(super) fn flip_from(&mut self, mut queue: Vec<u32>) -> usize {
        let mut queued = vec![false; self.twins.len()];
        queue.retain(|&h| !std::mem::replace(&mut queued[h as usize], true));
        let mut flips = 0;
        // Each flip strictly lowers a bounded energy; the cap only guards rounding.
        let cap = 50 * self.twins.len() + 1000;
        while let Some(h) = queue.pop() {
            queued[h as usize] = false;
            if flips >= cap || !self.should_flip(h) {
                continue;
            }
            let outer = self.flip(h);
            flips += 1;
            for o in outer {
                if o != NO_TWIN && !queued[o as usize] {
                    queued[o as usize] = true;
                    queue.push(o);
                }
            }
        }
        flips
    }

    /// Whether the edge of `h` is interior, not Delaunay and can be flipped.
    fn should_flip(&self, h: u32) -> bool {
        let twin = self.twins[h as usize];
        if twin == NO_TWIN {
            return false;
        }
        let (f, k) = split(h);
        let (g, j) = split(twin);
        if f == g || self.faces[f][(k + 2) % 3] == self.faces[g][(j + 2) % 3] {
            return false;
        }
        let (Some(alpha), Some(beta)) = (self.cotan_across(f, k), self.cotan_across(g, j)) else {
            return false;
        };
        alpha + beta < -1.0e-12
    }

    /// Flips the edge of `h` (triangles a b c and b a d become c a d and d b c) and
    /// returns the four outer half-edges, whose edges may have stopped being Delaunay.
    fn flip(&mut self, h: u32) -> [u32; 4] {
        let twin = self.twins[h as usize];
        let (f, k) = split(h);
        let (g, j) = split(twin);
        let (a, b, c) = (
            self.faces[f][k],
            self.faces[f][(k + 1) % 3],
            self.faces[f][(k + 2) % 3],
        );
        let d = self.faces[g][(j + 2) % 3];
        let [l_ab, l_bc, l_ca] = [0, 1, 2].map(|i| self.lengths[f][(k + i) % 3]);
        let [_, l_ad, l_db] = [0, 1, 2].map(|i| self.lengths[g][(j + i) % 3]);
        let [t_bc, t_ca] = [1, 2].map(|i| self.twins[half_edge(f, k + i) as usize]);
        let [t_ad, t_db] = [1, 2].map(|i| self.twins[half_edge(g, j + i) as usize]);
        let l_cd = diagonal_length(l_ab, l_bc, l_ca, l_ad, l_db);
        self.faces[f] = [c, a, d];
        self.lengths[f] = [l_ca, l_ad, l_cd];
        self.faces[g] = [d, b, c];
        self.lengths[g] = [l_db, l_bc, l_cd];
        let links = [
            (half_edge(f, 0), t_ca),
            (half_edge(f, 1), t_ad),
            (half_edge(f, 2), half_edge(g, 2)),
            (half_edge(g, 0), t_db),
            (half_edge(g, 1), t_bc),
        ];
        for (inner, outer) in links {
            self.twins[inner as usize] = outer;
            if outer != NO_TWIN {
                self.twins[outer as usize] = inner;
            }
        }
        [t_ca, t_ad, t_db, t_bc]
    }
}

/// The length of the diagonal c–d of the quad a d b c made by triangles a b c and b a d,
/// unfolded into the plane.
fn diagonal_length(l_ab: f64, l_bc: f64, l_ca: f64, l_ad: f64, l_db: f64) -> f64 {
    let apex = |to_a: f64, to_b: f64, side: f64| {
        let x = (l_ab * l_ab + to_a * to_a - to_b * to_b) / (2.0 * l_ab);
        let area = area_from_lengths(l_ab, to_a, to_b);
        glam::DVec2::new(x, side * 2.0 * area / l_ab)
    };
    apex(l_ca, l_bc, 1.0).distance(apex(l_ad, l_db, -1.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;

    /// A flat quad split along its long diagonal into two obtuse slivers.
    fn bad_quad() -> Triangulation {
        let mut mesh = Mesh::default();
        for p in [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 0.0, 0.05],
            [0.5, 0.0, -0.05],
        ] {
            mesh.push_vertex(p, [0.0, 1.0, 0.0], [0.0, 0.0]);
        }
        mesh.indices = vec![0, 1, 2, 1, 0, 3];
        Triangulation::from_mesh(&mesh)
    }

    #[test]
    fn flipping_replaces_the_long_diagonal_by_the_short_one() {
        let mut quad = bad_quad();
        assert_eq!(quad.flip_to_delaunay(), 1);
        let diagonal = quad.lengths[0][2];
        assert!((diagonal - 0.1).abs() < 1e-6, "{diagonal}");
        let total: f64 = (0..2).map(|f| quad.area(f)).sum();
        assert!((total - 0.05).abs() < 1e-9, "area is kept: {total}");
        for f in 0..2 {
            for k in 0..3 {
                assert!(quad.cotan_across(f, k).unwrap() > -1e-12);
            }
        }
        assert_eq!(quad.flip_to_delaunay(), 0, "already Delaunay");
    }

    #[test]
    fn mollification_gives_flat_triangles_an_area() {
        let mut mesh = Mesh::default();
        for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]] {
            mesh.push_vertex(p, [0.0, 1.0, 0.0], [0.0, 0.0]);
        }
        mesh.indices = vec![0, 1, 2];
        let mut flat = Triangulation::from_mesh(&mesh);
        assert_eq!(flat.area(0), 0.0);
        let epsilon = flat.mollify(1e-4);
        assert!(epsilon > 0.0 && flat.area(0) > 0.0);
    }
}
