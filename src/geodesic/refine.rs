//! Intrinsic refinement: edges split at their midpoints, the new vertices' edges to the
//! corners across measured within each (flat) triangle, so the surface is the same and
//! only its sampling is finer.

use super::triangulation::{NO_TWIN, Triangulation, half_edge, split};

impl Triangulation {
    /// Splits the edge of half-edge `h` at its midpoint, adding one vertex (numbered
    /// after the others) and one triangle on each side of the edge. Returns the vertex.
    pub fn split_edge(&mut self, h: u32) -> u32 {
        let m = self.vertex_count as u32;
        self.vertex_count += 1;
        let twin = self.twins[h as usize];
        let (f, k) = split(h);
        let f2 = self.split_side(f, k, m);
        if twin == NO_TWIN {
            return m;
        }
        let (g, j) = split(twin);
        let g2 = self.split_side(g, j, m);
        // f keeps a→m and g2 runs m→a; g keeps b→m and f2 runs m→b.
        self.link(half_edge(f, 0), half_edge(g2, 0));
        self.link(half_edge(g, 0), half_edge(f2, 0));
        m
    }

    /// Cuts triangle `f` (a b c, `k` the corner of a) by the segment from the midpoint
    /// `m` of a b to c: `f` becomes a m c, a new triangle m b c. Returns the new one.
    /// The halves of a b are left unpaired for the caller.
    fn split_side(&mut self, f: usize, k: usize, m: u32) -> usize {
        let [a, b, c] = [0, 1, 2].map(|i| self.faces[f][(k + i) % 3]);
        let [l_ab, l_bc, l_ca] = [0, 1, 2].map(|i| self.lengths[f][(k + i) % 3]);
        let [_, t_bc, t_ca] = [0, 1, 2].map(|i| self.twins[half_edge(f, k + i) as usize]);
        let half = 0.5 * l_ab;
        // The median from c (Apollonius), never below the triangle's own rounding.
        let l_mc = (0.5 * (l_bc * l_bc + l_ca * l_ca) - 0.25 * l_ab * l_ab)
            .max(0.0)
            .sqrt();
        let f2 = self.faces.len();
        self.faces[f] = [a, m, c];
        self.lengths[f] = [half, l_mc, l_ca];
        self.faces.push([m, b, c]);
        self.lengths.push([half, l_bc, l_mc]);
        self.twins.extend([NO_TWIN; 3]);
        self.twins[half_edge(f, 0) as usize] = NO_TWIN;
        self.link(half_edge(f, 1), half_edge(f2, 2));
        self.link(half_edge(f, 2), t_ca);
        self.link(half_edge(f2, 1), t_bc);
        f2
    }

    /// Pairs two half-edges (`other` may be [`NO_TWIN`]).
    fn link(&mut self, one: u32, other: u32) {
        self.twins[one as usize] = other;
        if other != NO_TWIN {
            self.twins[other as usize] = one;
        }
    }

    /// Intrinsic refinement for the heat method: splits every edge longer than
    /// [`REFINED_EDGE`] times the mean edge length, in rounds (at most one edge of a
    /// triangle a round, at most [`REFINE_ROUNDS`] rounds), flipping back to the Delaunay
    /// triangulation around each split, until none is longer or `budget` vertices have
    /// been added. Give it a Delaunay triangulation ([`Triangulation::flip_to_delaunay`]).
    /// Returns the vertices added and the flips made.
    ///
    /// Lengths are compared in steps of 2⁻²⁰ of the mean ([`LengthRanks`]), so that the
    /// rounding of a file's positions (an OBJ and a PLY of one mesh) does not change which
    /// edges are split; among equally long edges the first in triangle order goes first.
    pub fn refine(&mut self, budget: usize) -> (usize, usize) {
        let ranks = LengthRanks::new(self.mean_edge_length());
        let before = self.vertex_count;
        let mut flips = 0;
        for _ in 0..REFINE_ROUNDS {
            let chosen = self.longer_edges_apart(&ranks);
            if chosen.is_empty() || self.vertex_count - before >= budget {
                break;
            }
            let mut suspects = Vec::new();
            for h in chosen {
                if self.vertex_count - before >= budget {
                    break;
                }
                let twin = self.twins[h as usize];
                let new_faces = self.faces.len();
                self.split_edge(h);
                let mut around = vec![split(h).0, new_faces];
                if twin != NO_TWIN {
                    around.extend([split(twin).0, new_faces + 1]);
                }
                suspects.extend(
                    around
                        .iter()
                        .flat_map(|&f| (0..3).map(move |k| half_edge(f, k))),
                );
            }
            flips += self.flip_from(suspects);
        }
        (self.vertex_count - before, flips)
    }

    /// One half-edge of each edge longer than the refinement's limit, longest first, no
    /// two on the same triangle (the longer wins), so all of them can be split in one
    /// round.
    fn longer_edges_apart(&self, ranks: &LengthRanks) -> Vec<u32> {
        let mut long: Vec<(u64, u32)> = (0..self.twins.len() as u32)
            .filter(|&h| {
                let twin = self.twins[h as usize];
                twin == NO_TWIN || h < twin
            })
            .map(|h| (ranks.of(self.length(h)), h))
            .filter(|&(rank, _)| rank > ranks.limit)
            .collect();
        long.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
        let mut touched = vec![false; self.faces.len()];
        let mut chosen = Vec::new();
        for (_, h) in long {
            let twin = self.twins[h as usize];
            let faces = [Some(split(h).0), (twin != NO_TWIN).then(|| split(twin).0)];
            if faces.iter().flatten().any(|&f| touched[f]) {
                continue;
            }
            for f in faces.into_iter().flatten() {
                touched[f] = true;
            }
            chosen.push(h);
        }
        chosen
    }
}

/// Edge lengths as whole steps of 2⁻²⁰ of a unit (the mean edge length), the refinement's
/// measure: lengths a rounding apart compare equal.
struct LengthRanks {
    step: f64,
    /// The rank above which an edge is split: [`REFINED_EDGE`] units.
    limit: u64,
}

impl LengthRanks {
    fn new(unit: f64) -> LengthRanks {
        let step = unit / f64::from(1u32 << 20);
        let mut ranks = LengthRanks { step, limit: 0 };
        ranks.limit = ranks.of(REFINED_EDGE * unit);
        ranks
    }

    fn of(&self, length: f64) -> u64 {
        // Saturates: an infinite or huge length ranks highest, NaN lowest.
        (length / self.step).round() as u64
    }
}

/// Edges longer than this multiple of the mean edge length are split by
/// [`Triangulation::refine`].
pub const REFINED_EDGE: f64 = 1.0;

/// The most rounds of splitting [`Triangulation::refine`] does: good meshes settle in
/// three or four; around a vertex where splits keep making long edges (a narrow cone, a
/// boundary corner) refinement would otherwise go on taking vertices.
pub const REFINE_ROUNDS: usize = 8;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geodesic::triangulation::tests::square;

    fn total_area(t: &Triangulation) -> f64 {
        (0..t.faces.len()).map(|f| t.area(f)).sum()
    }

    /// Every pairing is mutual and joins the same two vertices the other way round, with
    /// the same length.
    fn assert_consistent(t: &Triangulation) {
        for (h, &twin) in t.twins.iter().enumerate() {
            if twin == NO_TWIN {
                continue;
            }
            let h = h as u32;
            assert_eq!(t.twins[twin as usize], h);
            assert_eq!((t.tail(h), t.head(h)), (t.head(twin), t.tail(twin)));
            assert!((t.length(h) - t.length(twin)).abs() < 1e-12);
        }
    }

    #[test]
    fn splitting_the_shared_diagonal_gives_four_triangles_meeting_at_its_midpoint() {
        let mut square = square();
        let diagonal = (0..6u32)
            .find(|&h| square.twins[h as usize] != NO_TWIN)
            .expect("an interior edge");
        let m = square.split_edge(diagonal);
        assert_eq!((m, square.vertex_count, square.faces.len()), (4, 5, 4));
        assert_consistent(&square);
        assert!((total_area(&square) - 1.0).abs() < 1e-12);
        // The midpoint of the diagonal is half a diagonal from every corner.
        for (f, face) in square.faces.iter().enumerate() {
            for k in 0..3 {
                if face[k] == m || face[(k + 1) % 3] == m {
                    assert!((square.lengths[f][k] - 0.5f64.sqrt()).abs() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn splitting_a_boundary_edge_adds_one_triangle_and_keeps_the_boundary() {
        let mut square = square();
        let side = (0..6u32)
            .find(|&h| square.twins[h as usize] == NO_TWIN)
            .expect("a boundary edge");
        let length = square.length(side);
        square.split_edge(side);
        assert_eq!(square.faces.len(), 3);
        assert_consistent(&square);
        assert!((total_area(&square) - 1.0).abs() < 1e-12);
        let halves = (0..9u32)
            .filter(|&h| {
                square.twins[h as usize] == NO_TWIN
                    && (square.length(h) - 0.5 * length).abs() < 1e-12
            })
            .count();
        assert_eq!(halves, 2, "the side is now two boundary halves");
        assert!(square.boundary_vertices().iter().all(|&b| b));
    }

    #[test]
    fn refinement_keeps_the_surface_and_leaves_it_delaunay_and_even() {
        for name in ["genus2:12", "torus:16", "sphere:12"] {
            let mesh = crate::mesh::primitive(name).expect("a primitive");
            let mut t = Triangulation::from_mesh(&crate::geodesic::welded_for_distances(&mesh).0);
            let area = total_area(&t);
            t.flip_to_delaunay();
            let longest = REFINED_EDGE * t.mean_edge_length();
            let before = t.vertex_count;
            let (added, _) = t.refine(2 * before);
            assert!(added > 0, "{name}");
            assert_eq!(t.vertex_count, before + added);
            assert_consistent(&t);
            assert!(
                (total_area(&t) - area).abs() < 1e-9 * area,
                "{name}: the same surface"
            );
            for h in 0..t.twins.len() as u32 {
                assert!(
                    t.length(h) <= longest * (1.0 + 1e-6),
                    "{name}: edge {h} still long"
                );
                let twin = t.twins[h as usize];
                if twin != NO_TWIN {
                    let (f, k) = split(h);
                    let (g, j) = split(twin);
                    let sum = t.cotan_across(f, k).unwrap() + t.cotan_across(g, j).unwrap();
                    assert!(sum >= -1e-9, "{name}: edge {h} not Delaunay");
                }
            }
        }
    }

    #[test]
    fn refinement_stops_at_its_budget() {
        let mesh = crate::mesh::primitive("genus2:12").expect("a primitive");
        let mut t = Triangulation::from_mesh(&crate::geodesic::welded_for_distances(&mesh).0);
        t.flip_to_delaunay();
        let (added, _) = t.refine(10);
        assert_eq!(added, 10);
        assert_consistent(&t);
    }
}
