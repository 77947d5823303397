//! `veneer mesh`: what a mesh file (or primitive) is made of and what is wrong with it.

use super::Failure;
use super::output::out;
use clap::Args;

#[derive(Args)]
pub struct MeshArgs {
    #[arg(help = super::mesh_help())]
    mesh: String,
    /// Also report the mesh after welding vertices closer than this distance.
    #[arg(long, value_name = "TOLERANCE")]
    weld: Option<f32>,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
    /// Also write the mesh (welded when --weld is given) as an OBJ file, e.g. to feed a
    /// primitive such as `torus:320` to other tools.
    #[arg(long, value_name = "FILE.obj")]
    write: Option<std::path::PathBuf>,
}

impl MeshArgs {
    /// Adds the mesh file and the OBJ written to `plan`.
    pub fn plan(&self, plan: &mut veneer::fsutil::OutputPlan, job: Option<&str>) {
        super::plan_mesh_command(plan, job, &self.mesh, self.write.as_deref());
    }
}

pub fn run(args: MeshArgs) -> Result<(), Failure> {
    let mut mesh = veneer::mesh::Mesh::named(&args.mesh)?;
    let mut reports = vec![("as loaded", veneer::mesh::analyse(&mesh))];
    if let Some(tolerance) = args.weld {
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(Failure::new(format!(
                "--weld {tolerance}: expected a distance ≥ 0"
            )));
        }
        mesh = veneer::mesh::weld(&mesh, tolerance).0;
        reports.push(("welded", veneer::mesh::analyse(&mesh)));
    }
    if let Some(path) = &args.write {
        super::write_output(Some(path), mesh.to_obj().as_bytes())?;
    }
    if args.json {
        let entries: Vec<_> = reports
            .iter()
            .map(|(state, report)| serde_json::json!({ "state": state, "report": report }))
            .collect();
        out(serde_json::to_string_pretty(&entries)?)?;
    } else {
        for (state, report) in &reports {
            out(format!("{} ({state}): {report}", args.mesh))?;
        }
    }
    Ok(())
}
