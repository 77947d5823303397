//! The options every command that reads a graph's exposed parameters shares:
//! `--preset NAME`, `--params-file FILE` and `--set NAME=VALUE`.

use super::Failure;
use clap::Args;
use std::path::{Path, PathBuf};
use veneer::graph::Graph;
use veneer::graph::parameters::{Given, Overrides, ParameterFile};

/// Values for the graph's exposed parameters (see `veneer compile --describe`).
#[derive(Args, Clone, Debug, Default)]
pub struct ParameterArgs {
    /// Start from the graph's parameter preset NAME.
    #[arg(long, value_name = "NAME", value_parser = parse_preset_name)]
    pub preset: Option<String>,
    /// Parameter values from a RON or JSON file (`{"ring_frequency": 0.7}`), applied
    /// after the preset.
    #[arg(long, value_name = "FILE")]
    pub params_file: Option<PathBuf>,
    /// Set one exposed parameter, last of all: NAME=0.7, NAME=0.1,0.2,0.3,
    /// NAME=#ff8800, or a word (a choice's option, on/off). Repeatable.
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = parse_assignment)]
    pub set: Vec<(String, Given)>,
}

/// Reads a preset name: one that could name a file (`snapshot` names goldens after it).
fn parse_preset_name(name: &str) -> Result<String, String> {
    veneer::graph::names::file_name_part("preset", name)?;
    Ok(name.to_string())
}

/// Reads `name=value`.
fn parse_assignment(text: &str) -> Result<(String, Given), String> {
    let (name, value) = text
        .split_once('=')
        .ok_or_else(|| format!("'{text}' is not NAME=VALUE"))?;
    let name = name.trim();
    if name.is_empty() {
        return Err(format!("'{text}' names no parameter"));
    }
    Ok((name.to_string(), Given::parse(value)?))
}

impl ParameterArgs {
    /// The overrides these options ask for, the parameter file read.
    pub fn overrides(&self) -> Result<Overrides, Failure> {
        let mut values = Vec::new();
        if let Some(path) = &self.params_file {
            let file: ParameterFile = super::read_ron_or_json(path)?;
            values.extend(file.0);
        }
        values.extend(self.set.iter().cloned());
        Ok(Overrides {
            preset: self.preset.clone(),
            values,
        })
    }

    /// Adds `graph` and the parameter file, if any, to the files `plan` reads, as read by
    /// `job` (a batch's) or else the graph; gives that reader's name.
    pub fn plan_graph(
        &self,
        plan: &mut veneer::fsutil::OutputPlan,
        job: Option<&str>,
        graph: &Path,
    ) -> String {
        let by = super::by(job, graph);
        plan.reads(graph, &by);
        if let Some(path) = &self.params_file {
            plan.reads(path, &by);
        }
        by
    }

    /// Applies the options to `graph`, read from `path` (named in errors).
    pub fn apply(&self, graph: &mut Graph, path: &Path) -> Result<(), Failure> {
        self.overrides()?
            .apply(graph)
            .map_err(|error| Failure::new(format!("{}: {error}", path.display())))
    }
}
