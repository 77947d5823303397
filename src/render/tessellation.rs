//! Adaptive tessellation of a displaced material's mesh for one view: the material's
//! height, evaluated on the CPU at the same surface points the vertex stage will see,
//! decides where the mesh is refined (`mesh::refine_for_displacement`).

use super::mesh_view::MeshView;
use crate::eval::{Evaluator, Surface};
use crate::graph::CheckedGraph;
use crate::mesh::{Mesh, Refined, Refinement, SurfacePoint, refine_for_displacement};
use glam::Vec3;

/// What adaptive tessellation did to a render's mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tessellated {
    /// Levels that split at least one edge.
    pub levels: u32,
    /// Triangles before and after.
    pub triangles: (usize, usize),
    /// Whether the triangle limit stopped it short of the tolerance.
    pub limited: bool,
}

/// Refines `mesh` where the material of `graph` displaces it by more than the
/// refinement's tolerance, seen through `view` in an image `image_height` pixels high.
pub fn tessellate(
    graph: &CheckedGraph,
    mesh: &Mesh,
    view: &MeshView,
    image_height: u32,
    refinement: &Refinement,
) -> Refined {
    let evaluator = Evaluator::from_checked(graph.clone());
    let size = view.size.max(1.0e-6);
    let center = Vec3::from(view.center);
    // The vertex stage's displacement: the height (texture-space units) over the size.
    let height = |point: &SurfacePoint| {
        let surface = Surface {
            position: (Vec3::from(point.position) * view.size + center).to_array(),
            normal: point.normal,
            uv: point.uv,
            fields: point.fields,
            time: view.time,
        };
        evaluator.eval::<f32>(&surface).height / size
    };
    let pixels_per_unit = |position: Vec3| view.pixels_per_unit(image_height, position);
    refine_for_displacement(mesh, refinement, &height, &pixels_per_unit)
}
