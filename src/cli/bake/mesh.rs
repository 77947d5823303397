//! `veneer bake --mesh M` for the mesh's own maps: mesh maps per texel of its UV layout,
//! and high to low (`--from HIGH`), each with a progress bar.

use super::super::Failure;
use super::super::output::{note, out};
use super::{BakeArgs, MapArg};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use veneer::bake::{Map, MeshMap, TransferMap, TransferSettings, bake_mesh_maps, transfer};

/// `veneer bake --mesh LOW --from HIGH`: the high mesh's normal and height baked into
/// the low mesh's layout, and any mesh maps of the low mesh beside them.
pub(super) fn run_transfer(args: &BakeArgs, low: &str, high: &str) -> Result<(), Failure> {
    let mut transfers = Vec::new();
    for map in args.maps() {
        match map {
            MapArg::Material(Map::Normal) => transfers.push(TransferMap::Normal),
            MapArg::Material(Map::Height) => transfers.push(TransferMap::Height),
            MapArg::Material(other) => {
                return Err(Failure::new(format!(
                    "--from bakes the high mesh's normal and height and the low mesh's own maps ({}); '{}' is a material's map and needs a graph",
                    MeshMap::ALL.map(MeshMap::name).join(", "),
                    other.name()
                )));
            }
            MapArg::Mesh(_) => {}
        }
    }
    let stem = args.mesh_stem(low);
    let load = |name: &str| {
        veneer::mesh::Mesh::named(name).map_err(|error| Failure::new(error.to_string()))
    };
    let settings = TransferSettings {
        size: args.size,
        format: args.settings().format,
        cage: args.cage,
        convention: args.settings().normal,
    };
    let low_mesh = load(low)?.with_uv_layout(args.size);
    let high_mesh = load(high)?;
    let bar = ProgressBar::new(0).with_style(
        ProgressStyle::with_template("{prefix:>16} [{bar:40}] {pos}/{len} texels {elapsed}")
            .expect("valid template"),
    );
    bar.set_prefix("high to low");
    let transferred = transfer(
        &low_mesh,
        &high_mesh,
        &transfers,
        &settings,
        &stem,
        |done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        },
    )
    .map_err(|error| Failure::new(format!("{high} onto {low}: {error}")));
    bar.finish_and_clear();
    let transferred = transferred?;
    let mesh_maps = args.mesh_maps();
    let mesh_written = match mesh_maps.is_empty() {
        true => Vec::new(),
        false => bake_mesh(args, low, &mesh_maps, &[stem])?,
    };
    if transferred.missed_texels > 0 {
        note(format!(
            "warning: {} of {} texels ({:.2}%) of {low} found no surface of {high} within the cage (±{:.4}); they read flat. Raise --cage if {high} lies farther off {low}",
            transferred.missed_texels,
            transferred.covered_texels,
            100.0 * transferred.missed_share(),
            transferred.cage
        ))?;
    }
    if args.json {
        return out(serde_json::to_string_pretty(&serde_json::json!({
            "transfer": transferred,
            "mesh_maps": mesh_written,
        }))?);
    }
    for (map, path, bytes) in &transferred.maps {
        note(format!(
            "wrote {} ({}×{}, {bytes} bytes; {} from {high}, heights {:.4} to {:.4} within the cage ±{:.4})",
            path.display(),
            args.size,
            args.size,
            map.name(),
            transferred.heights.0,
            transferred.heights.1,
            transferred.cage
        ))?;
    }
    for map in &mesh_written {
        note(format!(
            "wrote {} ({} bytes)",
            map.path.display(),
            map.bytes
        ))?;
    }
    Ok(())
}

/// The mesh maps of `mesh` baked once and written for every stem, with a progress bar.
pub(super) fn bake_mesh(
    args: &BakeArgs,
    mesh: &str,
    maps: &[MeshMap],
    stems: &[PathBuf],
) -> Result<Vec<veneer::bake::BakedMeshMap>, Failure> {
    let settings = args.mesh_map_settings();
    settings
        .validate(maps)
        .map_err(|error| Failure::new(error.to_string()))?;
    let loaded = veneer::mesh::preview_mesh(mesh)
        .map_err(|error| Failure::new(format!("{mesh}: {error}")))?
        .with_uv_layout(settings.size);
    let bar = ProgressBar::new(0).with_style(
        ProgressStyle::with_template("{prefix:>16} [{bar:40}] {pos}/{len} texels {elapsed}")
            .expect("valid template"),
    );
    bar.set_prefix("mesh maps");
    let stem_refs: Vec<&std::path::Path> = stems.iter().map(PathBuf::as_path).collect();
    let written = bake_mesh_maps(&loaded, maps, &settings, &stem_refs, |done, total| {
        bar.set_length(total);
        bar.set_position(done);
    })
    .map_err(|error| Failure::new(format!("{mesh}: {error}")));
    bar.finish_and_clear();
    written
}
