//! `veneer import`: a MaterialX document read back as a graph file.

use super::{Failure, by, output_file, write_output};
use clap::Args;
use std::path::PathBuf;
use veneer::fsutil::{Naming, OutputPlan};

#[derive(Args)]
pub struct ImportArgs {
    /// The MaterialX document (made of standard nodes Veneer has and Veneer's own node
    /// definitions, as `veneer compile --target mtlx --tier procedural` writes).
    document: PathBuf,
    /// The graph file to write (stdout when absent or `-`).
    #[arg(short, long)]
    output: Option<PathBuf>,
}

impl ImportArgs {
    /// Adds the document and the graph written to `plan`.
    pub fn plan(&self, plan: &mut OutputPlan, job: Option<&str>) {
        let by = by(job, &self.document);
        plan.reads(&self.document, &by);
        if let Some(output) = self.output.as_deref().and_then(output_file) {
            plan.writes(output, Naming::Given, &by);
        }
    }
}

pub fn run(args: ImportArgs) -> Result<(), Failure> {
    let name = args.document.display().to_string();
    let text = std::fs::read_to_string(&args.document)
        .map_err(|error| Failure::new(format!("{name}: cannot read: {error}")))?;
    let graph = veneer::bake::import_materialx(&text, &name).map_err(Failure::new)?;
    let ron = veneer::graph::to_ron(&graph);
    write_output(args.output.as_ref(), ron.as_bytes())
}
