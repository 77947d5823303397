//! The mesh loaders on arbitrary bytes, each input read as OBJ, STL, PLY and glTF/GLB:
//! a mesh or an error, never a panic; every mesh that loads has indices in range and
//! finite coordinates, and its report (the `veneer mesh` analysis) runs.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    for extension in ["obj", "stl", "ply", "glb"] {
        let Ok(mesh) = veneer::mesh::from_bytes(extension, bytes, None) else {
            continue;
        };
        let count = mesh.positions.len();
        assert!(mesh.indices.iter().all(|&i| (i as usize) < count));
        assert!(mesh.positions.iter().flatten().all(|c| c.is_finite()));
        assert_eq!(mesh.normals.len(), count);
        assert_eq!(mesh.uvs.len(), count);
        let _ = veneer::mesh::analyse(&mesh).problems();
    }
});
