//! Mesh fields computed before, kept by the content of the mesh they were computed on
//! (positions, normals, triangles) and the field's settings, so that an edit elsewhere
//! in the graph, a new distance field or a second render of the same mesh costs nothing.

use super::{MeshField, MeshFieldError};
use crate::mesh::Mesh;
use std::hash::{Hash, Hasher};
use std::sync::{Arc, Mutex};

/// How many fields are kept (the oldest go first): four lanes of two meshes.
const KEPT: usize = 8;

/// A computed field: the content hash of its mesh, its settings (a key) and its values.
type Entry = (u64, MeshField, Arc<Vec<f32>>);

static CACHE: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

/// A hash of what a mesh field depends on.
fn content(mesh: &Mesh) -> u64 {
    let mut hasher = rustc_hash::FxHasher::default();
    bytemuck::cast_slice::<[f32; 3], u8>(&mesh.positions).hash(&mut hasher);
    bytemuck::cast_slice::<[f32; 3], u8>(&mesh.normals).hash(&mut hasher);
    mesh.indices.hash(&mut hasher);
    hasher.finish()
}

/// `field` over `mesh`, from the cache when it was computed on the same content before.
pub fn cached(
    field: MeshField,
    mesh: &Mesh,
    progress: impl FnMut(usize, usize),
) -> Result<Arc<Vec<f32>>, MeshFieldError> {
    let (hash, key) = (content(mesh), field.key());
    let found = lock()
        .iter()
        .find(|(h, k, _)| *h == hash && *k == key)
        .map(|(_, _, values)| values.clone());
    if let Some(values) = found {
        return Ok(values);
    }
    let values = Arc::new(key.compute(mesh, progress)?);
    let mut cache = lock();
    if cache.len() >= KEPT {
        cache.remove(0);
    }
    cache.push((hash, key, values.clone()));
    Ok(values)
}

/// The cache, even after a panic elsewhere left its lock poisoned (entries are pushed
/// whole, so what it holds is sound).
fn lock() -> std::sync::MutexGuard<'static, Vec<Entry>> {
    CACHE
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh_fields::MeshFieldKind;

    #[test]
    fn the_same_content_and_settings_are_computed_once() {
        let torus = crate::mesh::primitive("torus:10").unwrap();
        let field = MeshField::new(MeshFieldKind::Thickness);
        let first = cached(field, &torus, |_, _| {}).unwrap();
        let mut computed = false;
        let again = cached(field, &torus, |_, _| computed = true).unwrap();
        assert!(Arc::ptr_eq(&first, &again) && !computed);
        // Ignored settings change nothing; another mesh is computed anew.
        let same = MeshField { radius: 9, ..field };
        assert!(Arc::ptr_eq(
            &first,
            &cached(same, &torus, |_, _| {}).unwrap()
        ));
        let mut moved = torus.clone();
        moved.positions[0][0] += 0.01;
        assert!(!Arc::ptr_eq(
            &first,
            &cached(field, &moved, |_, _| {}).unwrap()
        ));
    }
}
