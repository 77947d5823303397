//! Distance fields as vertex attributes: a graph's field sources (vertices counted as
//! the mesh file lists them) solved over its preview mesh and stored, normalised, in
//! `Mesh::fields` for `VeneerSurface.fields`.

use super::{Method, WeldedMesh, fields, max_finite};
use crate::graph::FieldSource;
use crate::mesh::Mesh;

/// Why fields could not be attached.
#[derive(Debug, thiserror::Error)]
pub enum FieldError {
    #[error(
        "field {slot}: source vertex {vertex} does not exist (the mesh has {count} vertices); a graph's field sources are vertices of its preview mesh: pick sources on this mesh in the editor (Distance fields → pick), or export onto the preview mesh"
    )]
    NoSuchVertex {
        slot: usize,
        vertex: u32,
        count: usize,
    },
    #[error("field {slot} has no source vertices")]
    NoSources { slot: usize },
    #[error("{0} fields given; a mesh carries at most 4")]
    TooMany(usize),
    #[error(transparent)]
    Heat(#[from] super::HeatError),
}

/// Checks field settings against a mesh file of `count` vertices without solving anything:
/// at most four fields, sources on existing vertices, a source for every used slot, and
/// settings the method accepts. `veneer check` asks this of what a render would solve.
pub fn check_field_sources(
    sources: &[FieldSource],
    count: usize,
    used: [bool; 4],
) -> Result<(), FieldError> {
    if sources.len() > 4 {
        return Err(FieldError::TooMany(sources.len()));
    }
    for (slot, field) in sources.iter().enumerate() {
        if field.sources.is_empty() && used[slot] {
            return Err(FieldError::NoSources { slot });
        }
        if let Some(&vertex) = field.sources.iter().find(|&&v| v as usize >= count) {
            return Err(FieldError::NoSuchVertex {
                slot,
                vertex,
                count,
            });
        }
        field.method.validate().map_err(super::HeatError::from)?;
    }
    Ok(())
}

/// Solves the fields of `sources` whose slot is marked in `used` over `mesh` and stores
/// them in `mesh.fields`, each divided by its largest finite distance. Vertices a field
/// never reaches read 1 (the material never gets there); unused or missing slots read 0.
/// Nothing is solved, and `mesh.fields` stays empty, when no slot is used. Returns a
/// note for each field the robust heat method solved in place of the plain one, and for
/// each the heat method solved unrefined because the mesh is too large to refine.
pub fn attach_fields(
    mesh: &mut Mesh,
    sources: &[FieldSource],
    used: [bool; 4],
    mut progress: impl FnMut(usize, usize),
) -> Result<Vec<String>, FieldError> {
    check_field_sources(sources, mesh.file_vertex_count(), used)?;
    let wanted: Vec<usize> = (0..sources.len()).filter(|&slot| used[slot]).collect();
    mesh.fields.clear();
    let mut notes = Vec::new();
    if wanted.is_empty() {
        return Ok(notes);
    }
    let welded = WeldedMesh::new(mesh);
    let mut methods: Vec<Method> = Vec::new();
    for &slot in &wanted {
        if !methods.contains(&sources[slot].method) {
            methods.push(sources[slot].method);
        }
    }
    let count = welded.mesh.positions.len();
    let total = wanted.len() * count;
    let mut done = 0;
    let mut attached = vec![[0.0; 4]; mesh.positions.len()];
    for method in methods {
        let slots: Vec<usize> = wanted
            .iter()
            .copied()
            .filter(|&s| sources[s].method == method)
            .collect();
        let sets: Vec<Vec<u32>> = slots
            .iter()
            .map(|&slot| welded.sources(&sources[slot].sources))
            .collect();
        let solved = fields(&welded.mesh, &sets, method, |d, _| {
            progress(done + d, total)
        })?;
        done += slots.len() * count;
        for (&slot, field) in slots.iter().zip(&solved.fields) {
            if let Some(fallback) = &solved.fallback {
                notes.push(format!("field {slot}: {fallback}"));
            }
            if let Some(note) = solved.heat.and_then(|heat| heat.refinement_note()) {
                notes.push(format!("field {slot}: {note}"));
            }
            let farthest = max_finite(field);
            for (vertex, &target) in welded.of_vertex.iter().enumerate() {
                let distance = field[target as usize];
                attached[vertex][slot] = match distance.is_finite() {
                    true if farthest > 0.0 => (distance / farthest) as f32,
                    true => 0.0,
                    false => 1.0,
                };
            }
        }
    }
    mesh.fields = attached;
    Ok(notes)
}
