//! glTF 2.0 export (`veneer bake --gltf`): a material baked onto its preview mesh (or
//! another mesh, [`super::model`]) and wired into a `pbrMetallicRoughness` material —
//! base colour (sRGB), occlusion-roughness-metallic packed as glTF reads it (R, G, B),
//! an OpenGL-convention normal map, emission with `KHR_materials_emissive_strength`
//! past 1 — on that mesh with its normals, UVs and tangents.

mod document;

use document::MaterialData;
pub use document::Packaging;

use super::BakeError;
use super::model::{ModelSettings, bake_model, model_stem, textures_beside};
use crate::codegen::{AlphaUse, Compiled};
use crate::fsutil::Naming;
use crate::render::GpuContext;
use serde_json::json;
use std::path::{Path, PathBuf};

/// How an export to `path` is packaged: `.gltf` with its buffer and PNGs beside it, or
/// else (`.glb`, any other name) one binary file.
fn packaging(path: &Path) -> Packaging {
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("gltf") => Packaging::Separate,
        _ => Packaging::Binary,
    }
}

/// Every file an export to `path` may write, `path` itself first: a `.gltf` has its
/// buffer and up to four textures beside it (emission and normal only when the material
/// has them).
pub fn gltf_files(path: &Path) -> Vec<PathBuf> {
    let mut files = vec![path.to_path_buf()];
    if packaging(path) == Packaging::Separate {
        files.push(path.with_file_name(document::buffer_name(&model_stem(path))));
        files.extend(textures_beside(path));
    }
    files
}

/// Exports `compiled` (parameters baked) to `path` (`.glb`, or `.gltf` with its buffer and
/// PNGs beside it), calling `progress(done, total)` as tiles render: once it answers
/// `false`, the export stops after the map being rendered ([`BakeError::Cancelled`],
/// nothing written). The files are put in
/// place together once all are written, so a failed export leaves none of them; the
/// files beside a `.gltf` are named by Veneer and never written through links
/// ([`crate::fsutil::Naming::Implied`]). The paths written come back, the document first.
pub fn export_gltf(
    gpu: &GpuContext,
    compiled: &Compiled,
    settings: &ModelSettings,
    path: &Path,
    progress: impl FnMut(u64, u64) -> bool,
) -> Result<Vec<PathBuf>, BakeError> {
    let packaging = packaging(path);
    super::output_folder(path)?;
    let stem = model_stem(path);
    let model = bake_model(gpu, compiled, settings, &stem, path, progress)?;
    let mut material = json!({ "name": model.name });
    let mut extensions = Vec::new();
    // Base colour, with alpha where the material's alpha shows.
    material["pbrMetallicRoughness"] = json!({ "baseColorTexture": { "index": 0 } });
    match model.alpha {
        AlphaUse::Opaque => {}
        AlphaUse::Mask(cutoff) => {
            material["alphaMode"] = json!("MASK");
            material["alphaCutoff"] = json!(cutoff);
        }
        AlphaUse::Blend => material["alphaMode"] = json!("BLEND"),
    }
    if model.alpha != AlphaUse::Opaque {
        // The preview draws the back faces of what can be cut away or seen through.
        material["doubleSided"] = json!(true);
    }
    // Occlusion, roughness, metallic in one texture.
    material["pbrMetallicRoughness"]["metallicRoughnessTexture"] = json!({ "index": 1 });
    if model.occluded {
        material["occlusionTexture"] = json!({ "index": 1 });
    }
    let mut textures = vec![model.base_color, model.orm];
    if let Some((emission, strength)) = model.emission {
        material["emissiveTexture"] = json!({ "index": textures.len() });
        material["emissiveFactor"] = json!([1.0, 1.0, 1.0]);
        textures.push(emission);
        if strength > 1.0 {
            material["extensions"] =
                json!({ "KHR_materials_emissive_strength": { "emissiveStrength": strength } });
            extensions.push("KHR_materials_emissive_strength");
        }
    }
    if let Some(normal) = model.normal {
        material["normalTexture"] = json!({ "index": textures.len() });
        textures.push(normal);
    }
    let material = MaterialData {
        json: material,
        extensions,
        textures,
    };
    let files = document::document(&stem, &model.mesh, &material, packaging);
    // The document is the file the user named; the rest go beside it.
    let targets: Vec<(PathBuf, Naming)> = (files.iter().enumerate())
        .map(|(index, (file_name, _))| match index {
            0 => (path.to_path_buf(), Naming::Given),
            _ => (path.with_file_name(file_name), Naming::Implied),
        })
        .collect();
    let writes = (targets.iter().zip(&files))
        .map(|((target, naming), (_, bytes))| (target.as_path(), *naming, bytes.as_slice()));
    crate::fsutil::write_together(writes)
        .map_err(|(path, error)| BakeError::Write { path, error })?;
    Ok(targets.into_iter().map(|(target, _)| target).collect())
}
