//! The mesh preview's vertex stage for materials with a height output: each vertex is
//! moved along its normal by the material's height (in texture-space units), so
//! silhouettes change as well as shading. Added to the module only when used.

@vertex
fn veneer_mesh_vertex_displaced(input: VeneerVertexIn) -> VeneerVertexOut {
    let normal = normalize(input.normal);
    let surface = VeneerSurface(veneer_texture_position(input.position), normal, input.uv, input.fields, veneer_mesh_view.time);
    let height = veneer_material(surface).height;
    return veneer_vertex_at(input, input.position + normal * height / max(veneer_mesh_view.placement.w, 1.0e-6));
}
