//! `veneer compile`: the material as a shader module for WGSL or another engine's language.

use super::{Failure, in_file, load_graph, write_output};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};
use veneer::bake::{MaterialxSettings, SurfaceModel, Tier, export_materialx, materialx_files};
use veneer::codegen::export::{Target, export_compiled};
use veneer::codegen::manifest::export_beside;
use veneer::codegen::{CompileOptions, ParamMode, compile, describe_parameters};
use veneer::fsutil::{Naming, OutputPlan, write_together};

/// How parameters appear in the output.
#[derive(Clone, Copy, ValueEnum)]
pub enum ParamsArg {
    /// As literal constants: no bindings needed.
    Baked,
    /// The exposed parameters as named members of one uniform struct
    /// (`veneer_params: VeneerParameters`, group 1 binding 0); every other constant baked.
    Uniform,
    /// Every constant as a slot of one uniform block (`veneer_params`, group 1 binding
    /// 0, one vec4 per slot), as the editor's live preview binds them.
    Slots,
}

/// What `--target` names: a shader language, or a MaterialX document.
#[derive(Clone, Copy, PartialEq)]
enum TargetArg {
    Shader(Target),
    Materialx,
}

impl ValueEnum for TargetArg {
    fn value_variants<'a>() -> &'a [Self] {
        const TARGETS: [TargetArg; 7] = [
            TargetArg::Shader(Target::ALL[0].0),
            TargetArg::Shader(Target::ALL[1].0),
            TargetArg::Shader(Target::ALL[2].0),
            TargetArg::Shader(Target::ALL[3].0),
            TargetArg::Shader(Target::ALL[4].0),
            TargetArg::Shader(Target::ALL[5].0),
            TargetArg::Materialx,
        ];
        &TARGETS
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        match self {
            TargetArg::Shader(target) => target.to_possible_value(),
            TargetArg::Materialx => Some(clap::builder::PossibleValue::new("mtlx").help(
                "MaterialX 1.39 document: the material's maps baked beside it, wired into a surface shader",
            )),
        }
    }
}

/// The surface shader a MaterialX export wires its maps into.
#[derive(Clone, Copy)]
struct SurfaceArg(SurfaceModel);

impl ValueEnum for SurfaceArg {
    fn value_variants<'a>() -> &'a [Self] {
        const MODELS: [SurfaceArg; 3] = [
            SurfaceArg(SurfaceModel::ALL[0].0),
            SurfaceArg(SurfaceModel::ALL[1].0),
            SurfaceArg(SurfaceModel::ALL[2].0),
        ];
        &MODELS
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        let (_, name, node) = SurfaceModel::ALL
            .iter()
            .find(|(model, _, _)| *model == self.0)?;
        Some(clap::builder::PossibleValue::new(*name).help(*node))
    }
}

/// `--tier`: how a MaterialX export keeps the material.
#[derive(Clone, Copy)]
struct TierArg(Tier);

impl ValueEnum for TierArg {
    fn value_variants<'a>() -> &'a [Self] {
        const TIERS: [TierArg; 3] = [
            TierArg(Tier::ALL[0].0),
            TierArg(Tier::ALL[1].0),
            TierArg(Tier::ALL[2].0),
        ];
        &TIERS
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        let help = match self.0 {
            Tier::Baked => "every map baked, read by image nodes",
            Tier::Procedural => "the graph translated node by node",
            Tier::Auto => "procedural where every node translates, else baked",
        };
        Some(clap::builder::PossibleValue::new(self.0.name()).help(help))
    }
}

#[derive(Args)]
pub struct CompileArgs {
    /// The graph file.
    graph: PathBuf,
    /// Shader language of the output, or `mtlx` for a MaterialX document.
    #[arg(long, value_enum, default_value = "wgsl")]
    target: TargetArg,
    /// With `--target mtlx`: the surface shader the material is wired into [default:
    /// open-pbr].
    #[arg(long, value_enum)]
    surface: Option<SurfaceArg>,
    /// With `--target mtlx`: how the material is kept [default: baked].
    #[arg(long, value_enum)]
    tier: Option<TierArg>,
    /// With `--target mtlx`: width and height in pixels of every map baked (the procedural
    /// tier's normal map and field textures too) [default: 1024].
    #[arg(long)]
    size: Option<u32>,
    /// Parameters baked as constants, exposed ones in a named uniform struct, or every
    /// constant in a block of slots.
    #[arg(long, value_enum, default_value = "baked")]
    params: ParamsArg,
    /// Output file (stdout when absent or `-`). With `--params uniform`, the JSON
    /// description of the parameters is written beside it as `<stem>.parameters.json`
    /// (unless it is a device or a pipe).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Print the JSON description of the exposed parameters instead of the shader.
    #[arg(long)]
    describe: bool,
    #[command(flatten)]
    parameters: super::parameters::ParameterArgs,
}

impl CompileArgs {
    /// Adds the graph, the parameter file, the output and the description written beside
    /// it to `plan`.
    pub fn plan(&self, plan: &mut OutputPlan, job: Option<&str>) {
        let by = self.parameters.plan_graph(plan, job, &self.graph);
        if let Some(output) = self.output.as_deref().and_then(super::output_file) {
            if self.target == TargetArg::Materialx {
                plan.writes_beside(&materialx_files(output), &by);
                return;
            }
            plan.writes(output, Naming::Given, &by);
            if self.describes_beside() {
                plan.writes(description_path(output), Naming::Implied, &by);
            }
        }
    }

    fn param_mode(&self) -> ParamMode {
        match self.params {
            ParamsArg::Baked => ParamMode::Baked,
            ParamsArg::Uniform => ParamMode::Named,
            ParamsArg::Slots => ParamMode::Uniform,
        }
    }

    /// Whether the parameters' description goes beside the shader file: with `--params
    /// uniform`, when the shader goes to a file (not to stdout, a device or a pipe).
    fn describes_beside(&self) -> bool {
        let file = (self.output.as_deref().and_then(super::output_file))
            .is_some_and(|output| !veneer::fsutil::is_stream(output));
        file && !self.describe && self.param_mode() == ParamMode::Named
    }
}

pub fn run(args: CompileArgs) -> Result<(), Failure> {
    let mut graph = load_graph(&args.graph)?;
    args.parameters.apply(&mut graph, &args.graph)?;
    let target = match args.target {
        TargetArg::Shader(target) => target,
        TargetArg::Materialx => return run_materialx(&args, &graph),
    };
    if args.surface.is_some() || args.tier.is_some() || args.size.is_some() {
        return Err(Failure::new(
            "--surface, --tier and --size shape a MaterialX export: give them with --target mtlx",
        ));
    }
    let params = args.param_mode();
    let compiled = compile(&graph, &CompileOptions::with_params(params))
        .map_err(|error| in_file(&args.graph, error))?;
    let description = describe_parameters(&compiled);
    if args.describe {
        return write_output(args.output.as_ref(), description.as_bytes());
    }
    if !compiled.passes.is_empty() {
        return write_passes(&args, &compiled, target);
    }
    let bytes = export_compiled(&compiled, target).map_err(|error| in_file(&args.graph, error))?;
    match args.output.as_deref().and_then(super::output_file) {
        Some(path) if args.describes_beside() && !super::names_folder(path) => write_both(
            path,
            &bytes,
            &description_path(path),
            description.as_bytes(),
        ),
        _ => write_output(args.output.as_ref(), &bytes),
    }
}

/// Writes a multi-pass material's modules and manifest together beside the output file
/// (which names the material's module): a half-written export is never left.
fn write_passes(
    args: &CompileArgs,
    compiled: &veneer::codegen::Compiled,
    target: Target,
) -> Result<(), Failure> {
    let output = match args.output.as_deref().and_then(super::output_file) {
        Some(path) if !veneer::fsutil::is_stream(path) && !super::names_folder(path) => path,
        _ => {
            return Err(Failure::new(format!(
                "{}: the material renders {} passes, exported as a module each and a manifest: give `-o FILE` (the material's module; the others go beside it)",
                args.graph.display(),
                compiled.passes.passes.len()
            )));
        }
    };
    let files =
        export_beside(compiled, target, output).map_err(|error| in_file(&args.graph, error))?;
    let description = describe_parameters(compiled);
    let described = args.describes_beside().then(|| description_path(output));
    let mut writes: Vec<(&Path, Naming, &[u8])> = (files.iter())
        .map(|(path, naming, bytes)| (path.as_path(), *naming, bytes.as_slice()))
        .collect();
    if let Some(path) = &described {
        writes.push((path.as_path(), Naming::Implied, description.as_bytes()));
    }
    write_together(writes).map_err(|(path, error)| {
        Failure::new(format!("{}: cannot write: {error}", path.display()))
    })?;
    super::output::note(format_args!(
        "wrote {} and {} passes with their manifest {}",
        output.display(),
        compiled.passes.passes.len(),
        files.last().expect("the manifest").0.display()
    ))
}

/// `veneer compile --target mtlx`: the material's maps baked beside a MaterialX document
/// that wires them into a surface shader.
fn run_materialx(args: &CompileArgs, graph: &veneer::graph::Graph) -> Result<(), Failure> {
    let output = match args.output.as_deref().and_then(super::output_file) {
        Some(path) if !veneer::fsutil::is_stream(path) && !super::names_folder(path) => path,
        _ => {
            return Err(Failure::new(format!(
                "{}: a MaterialX export is a document with its maps beside it: give `-o FILE.mtlx`",
                args.graph.display()
            )));
        }
    };
    let size = args.size.unwrap_or(1024);
    if size == 0 {
        return Err(Failure::new("--size must be at least 1"));
    }
    if args.describe || !matches!(args.params, ParamsArg::Baked) {
        return Err(Failure::new(
            "--target mtlx keeps the parameters in the document (baked into its maps, or as its node graph's inputs): leave out --params and --describe",
        ));
    }
    let compiled =
        compile(graph, &CompileOptions::default()).map_err(|error| in_file(&args.graph, error))?;
    let gpu = veneer::render::GpuContext::new()?;
    let settings = MaterialxSettings {
        tier: args.tier.map_or(Tier::Baked, |tier| tier.0),
        surface: args
            .surface
            .map_or(SurfaceModel::OpenPbr, |surface| surface.0),
        size,
        time: 0.0,
    };
    let bar = indicatif::ProgressBar::new(0).with_style(
        indicatif::ProgressStyle::with_template(
            "{prefix:>16} [{bar:40}] {pos}/{len} tiles {elapsed}",
        )
        .expect("valid template"),
    );
    bar.set_prefix("MaterialX");
    let written = export_materialx(&gpu, &compiled, &settings, output, |done, total| {
        bar.set_length(total);
        bar.set_position(done);
        true
    })
    .map_err(|error| in_file(&args.graph, error))?;
    bar.finish_and_clear();
    for node in &written.untranslatable {
        super::output::note(format_args!("baked: cannot translate {node}"))?;
    }
    for path in &written.files {
        let bytes = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
        super::output::note(format_args!("wrote {} ({bytes} bytes)", path.display()))?;
    }
    Ok(())
}

/// Writes the shader and its parameters' description together: neither is left
/// without the other.
fn write_both(shader: &Path, bytes: &[u8], description: &Path, text: &[u8]) -> Result<(), Failure> {
    let files = [
        (shader, Naming::Given, bytes),
        (description, Naming::Implied, text),
    ];
    write_together(files)
        .map_err(|(path, error)| Failure::new(format!("{}: cannot write: {error}", path.display())))
}

/// Where the parameter description of export `output` goes: `<stem>.parameters.json`
/// in its folder.
pub fn description_path(output: &std::path::Path) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    output.with_file_name(format!("{stem}.parameters.json"))
}
