//! `veneer check`: load, type-check, compile, validate and lint graph files.

use super::output::{note, out};
use super::{Failure, in_file};
use clap::Args;
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct CheckArgs {
    /// Graph files to check; numerical hazards are printed as warnings (they do not fail the check).
    #[arg(required = true)]
    graphs: Vec<PathBuf>,
}

/// What the nodes of `checked` report beyond hazards (a sampler: the cells it
/// searches), as `node 'label' (#id): sentence`.
fn reports(checked: &veneer::graph::CheckedGraph) -> Vec<String> {
    use veneer::graph::check::InputSource;
    let mut lines = Vec::new();
    for node in &checked.order {
        let constant = |pin: &str| match node.input(pin) {
            Some(InputSource::Const(value)) => Some(value.components()),
            _ => None,
        };
        if let Some(report) = node.node.kind.definition().report(&constant) {
            lines.push(format!("{}: {report}", node.node));
        }
    }
    lines
}

/// The lints of a graph that compiles. The lint runs on the second core while the
/// graph compiles and validates; both only read the checked graph.
fn check_one(path: &Path) -> Result<(Vec<veneer::lint::Lint>, Vec<String>), Failure> {
    let graph = veneer::graph::load(path)?;
    let checked = veneer::graph::check(&graph)
        .map_err(|errors| in_file(path, veneer::codegen::CompileError::Check(errors)))?;
    let positions = veneer::lint::preview_positions(&graph);
    let (module, lints) = std::thread::scope(|scope| {
        let lints = scope.spawn(|| veneer::lint::lint(&checked, positions));
        let module = veneer::codegen::compile_checked(&graph, &checked, &Default::default())
            .map(|(module, _)| module);
        (module, lints.join())
    });
    let lints = lints.map_err(|_| Failure::new(format!("{}: the lint failed", path.display())))?;
    let module = module.map_err(|error| in_file(path, error))?;
    check_preview_mesh(&graph, module.uses.fields).map_err(|error| in_file(path, error))?;
    let reports = reports(&checked);
    // A million-node graph is millions of allocations, a second to free: let the other
    // core do it while the next file is read (the process does not wait for it at exit).
    std::thread::spawn(move || drop((graph, checked, module)));
    Ok((lints, reports))
}

/// What a render would find wrong with the preview mesh: a mesh that does not load, or
/// field sources it does not have.
fn check_preview_mesh(graph: &veneer::graph::Graph, used_fields: [bool; 4]) -> Result<(), String> {
    let mesh =
        veneer::mesh::preview_mesh(&graph.preview.mesh).map_err(|error| error.to_string())?;
    veneer::geodesic::check_field_sources(
        &graph.preview.fields,
        mesh.file_vertex_count(),
        used_fields,
    )
    .map_err(|error| format!("preview mesh {}: {error}", graph.preview.mesh))
}

pub fn run(args: CheckArgs) -> Result<(), Failure> {
    let mut failures = Vec::new();
    for path in &args.graphs {
        match check_one(path) {
            Ok((lints, reports)) => {
                for report in reports {
                    note(format!("{}: {report}", path.display()))?;
                }
                let lines = lints.iter().map(|lint| format!("warning: {lint}"));
                for line in veneer::messages::summarise(lines) {
                    note(format!("{}: {line}", path.display()))?;
                }
                let warnings = match lints.len() {
                    0 => String::new(),
                    1 => " (1 warning)".to_string(),
                    count => format!(" ({count} warnings)"),
                };
                out(format!("{}: ok{warnings}", path.display()))?;
            }
            Err(Failure(message, _)) => failures.push(message),
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(Failure::new(failures.join("\n")))
    }
}
