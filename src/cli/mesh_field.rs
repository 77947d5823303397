//! `veneer mesh-field`: a mesh field (curvature, occlusion, thickness) over a mesh, one
//! line per vertex of its file.

use super::output::note;
use super::{Failure, write_output};
use clap::Args;
use std::path::PathBuf;
use std::time::Instant;
use veneer::mesh_fields::{MeshField, MeshFieldKind, Scene};

#[derive(Args)]
pub struct MeshFieldArgs {
    #[arg(help = super::mesh_help())]
    mesh: String,
    /// What the field measures.
    #[arg(long, value_enum)]
    kind: MeshFieldKind,
    /// Convexity: the radius it is measured at, in percent of the mesh's bounding radius
    /// (1 to 100).
    #[arg(long, default_value_t = 5)]
    radius: u32,
    /// Occlusion and thickness: rays per vertex (1 to 4096), the accuracy knob.
    #[arg(long, default_value_t = 64)]
    samples: u32,
    /// Occlusion and thickness: how far rays look, in percent of the bounding radius
    /// (1 to 400).
    #[arg(long, default_value_t = 50)]
    distance: u32,
    /// Occlusion: stop casting rays at a vertex once the 95% confidence interval of its
    /// value is narrower than ± this (at most --samples rays).
    #[arg(long)]
    tolerance: Option<f32>,
    /// Output CSV: one line per vertex of the file, in its order; `nan` for vertices no
    /// triangle uses.
    #[arg(short, long)]
    output: PathBuf,
}

impl MeshFieldArgs {
    /// Adds the mesh file and the CSV written to `plan`.
    pub fn plan(&self, plan: &mut veneer::fsutil::OutputPlan, job: Option<&str>) {
        super::plan_mesh_command(plan, job, &self.mesh, Some(&self.output));
    }

    fn field(&self) -> MeshField {
        MeshField {
            kind: self.kind,
            radius: self.radius,
            samples: self.samples,
            distance: self.distance,
        }
    }
}

pub fn run(args: MeshFieldArgs) -> Result<(), Failure> {
    let field = args.field();
    field
        .validate()
        .map_err(|error| Failure::new(error.to_string()))?;
    if let Some(tolerance) = args.tolerance
        && !(tolerance > 0.0 && tolerance < 1.0)
    {
        return Err(Failure::new(format!(
            "--tolerance {tolerance}: expected a half-width between 0 and 1"
        )));
    }
    let started = Instant::now();
    let mesh = veneer::mesh::Mesh::named(&args.mesh)?;
    // Seams split vertices that the fields see as one: report the welded surface.
    let welded = veneer::geodesic::welded_for_distances(&mesh).0;
    for problem in veneer::mesh::analyse(&welded).problems() {
        note(format!("warning: {}: {problem}", args.mesh))?;
    }
    let loaded = started.elapsed();
    let bar = field.kind.casts_rays().then(|| {
        let bar = indicatif::ProgressBar::new(mesh.positions.len() as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} {elapsed}")
                .expect("valid template"),
        );
        bar.set_message(field.to_string());
        bar
    });
    let progress = |done: usize, _: usize| {
        if let Some(bar) = &bar {
            bar.set_position(done as u64);
        }
    };
    let computing = Instant::now();
    let (values, rays) = match (field.kind, args.tolerance) {
        (MeshFieldKind::Occlusion, Some(tolerance)) => {
            let estimates = veneer::mesh_fields::occlusion(
                &Scene::new(&mesh),
                field.sampling(Some(tolerance)),
                progress,
            );
            let rays: u64 = estimates.iter().map(|e| u64::from(e.rays)).sum();
            let values = estimates.iter().map(|e| e.open).collect();
            (values, Some(rays as f64 / estimates.len().max(1) as f64))
        }
        _ => {
            let values = field
                .compute(&mesh, progress)
                .map_err(|error| Failure::new(format!("{}: {error}", args.mesh)))?;
            (
                values,
                field.kind.casts_rays().then_some(f64::from(field.samples)),
            )
        }
    };
    let computed = computing.elapsed();
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let values = in_file_order(&mesh, &values, &field);
    write_output(Some(&args.output), csv(&values).as_bytes())?;
    note(format!(
        "{}: {} vertices, {} triangles; {field}; load {:.1} ms, compute {:.1} ms{}",
        args.mesh,
        values.len(),
        mesh.triangle_count(),
        loaded.as_secs_f64() * 1e3,
        computed.as_secs_f64() * 1e3,
        rays.map_or(String::new(), |rays| format!(", {rays:.1} rays per vertex")),
    ))
}

/// The field at every vertex of the mesh's file (the first loaded copy of each; NaN for
/// vertices no triangle uses), thickness back in mesh units.
fn in_file_order(mesh: &veneer::mesh::Mesh, values: &[f32], field: &MeshField) -> Vec<f64> {
    let scale = match field.kind {
        // Thickness is a share of the distance, itself a share of the bounding radius:
        // the CSV gives mesh units.
        MeshFieldKind::Thickness => mesh.bounding_sphere().1 * f64::from(field.distance) / 100.0,
        _ => 1.0,
    };
    mesh.vertices_of_file()
        .into_iter()
        .map(|vertex| vertex.map_or(f64::NAN, |v| f64::from(values[v as usize]) * scale))
        .collect()
}

/// One line per vertex.
fn csv(values: &[f64]) -> String {
    let mut csv = String::with_capacity(values.len() * 12);
    for value in values {
        csv.push_str(&value.to_string());
        csv.push('\n');
    }
    csv
}
