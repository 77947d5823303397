//! The tangent frame a material's tangent-space normal is read in, shared by the mesh
//! preview and the bakes: x along +u, y up the image (towards -v, as OpenGL-convention
//! normal maps and glTF expect), z the surface normal.

// The frame at a fragment from the screen-space derivatives of its position and uv
// (a cotangent frame; no vertex tangents needed). Where the uv does not vary (no UV
// layout, the flat plane) the frame is built round the normal alone: x = normal × +z
// (+x on the plane y = 0), or +x where the normal is along z.
fn veneer_tangent_frame(position: vec3f, normal: vec3f, uv: vec2f) -> mat3x3f {
    let dp_x = dpdx(position);
    let dp_y = dpdy(position);
    let duv_x = dpdx(uv);
    let duv_y = dpdy(uv);
    let across_y = cross(dp_y, normal);
    let across_x = cross(normal, dp_x);
    let along_u = across_y * duv_x.x + across_x * duv_y.x;
    let along_v = across_y * duv_x.y + across_x * duv_y.y;
    let scale = max(dot(along_u, along_u), dot(along_v, along_v));
    if scale > 1.0e-30 && length(cross(along_u, along_v)) > 1.0e-9 * scale {
        let inverse = inverseSqrt(scale);
        return mat3x3f(along_u * inverse, -along_v * inverse, normal);
    }
    return veneer_frame_round(normal);
}

// A tangent frame built round a unit normal alone (see veneer_tangent_frame).
fn veneer_frame_round(normal: vec3f) -> mat3x3f {
    var tangent = cross(normal, vec3f(0.0, 0.0, 1.0));
    if dot(tangent, tangent) < 1.0e-12 {
        tangent = vec3f(1.0, 0.0, 0.0);
    }
    tangent = normalize(tangent);
    return mat3x3f(tangent, cross(normal, tangent), normal);
}

// How far a tangent-space normal tilts the frame's normal: the tilted normal minus the
// frame's, 0 for (0, 0, 1) exactly (so flat materials shade bit for bit as before) and
// for a zero vector.
fn veneer_tilt(frame: mat3x3f, normal: vec3f) -> vec3f {
    let length_squared = dot(normal, normal);
    if all(normal == vec3f(0.0, 0.0, 1.0)) || length_squared < 1.0e-20 {
        return vec3f(0.0);
    }
    return frame * (normal * inverseSqrt(length_squared)) - frame[2];
}
