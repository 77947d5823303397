//! Shader exports for other engines through naga's back-ends: GLSL (450 core and ES 300),
//! HLSL (SM 5.1), MSL and SPIR-V, next to the WGSL module itself. Every non-WGSL export
//! carries the fragment entry point of `shaders/export_entry.wgsl`; `veneer_material`
//! keeps its name. Each export is validated before it is returned: the module by naga's
//! validator, and GLSL 450 and SPIR-V once more by parsing the output back with naga
//! (naga reads only Vulkan-style GLSL, so GLSL ES 3.00 is checked by glslangValidator in
//! the tests instead).

use super::{CompileError, CompileOptions, Compiled, ParamMode, compile, validate};
use crate::graph::Graph;

/// A shader language Veneer exports to. Adding one is this file alone: a variant, its
/// line in [`Target::ALL`], its extension and its arm in [`export`]; the command line,
/// the editor's export dialog and the export tests list `ALL`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    Wgsl,
    /// GLSL 450 core: a complete fragment shader.
    Glsl,
    /// GLSL ES 3.00 (WebGL 2 and mobile): a complete fragment shader.
    GlslEs,
    /// HLSL shader model 5.1.
    Hlsl,
    /// Metal Shading Language 2.0.
    Msl,
    /// SPIR-V 1.0 binary.
    Spirv,
}

impl Target {
    /// Every target: its name on the command line and its description there.
    pub const ALL: [(Target, &str, &str); 6] = [
        (Target::Wgsl, "wgsl", "WGSL module (the DESIGN contract)"),
        (Target::Glsl, "glsl", "GLSL 450 core fragment shader"),
        (Target::GlslEs, "glsl-es", "GLSL ES 3.00 fragment shader"),
        (Target::Hlsl, "hlsl", "HLSL, shader model 5.1"),
        (Target::Msl, "msl", "Metal Shading Language 2.0"),
        (Target::Spirv, "spv", "SPIR-V binary"),
    ];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        Target::ALL
            .iter()
            .find(|(target, _, _)| *target == self)
            .map(|(_, name, _)| *name)
            .unwrap_or_default()
    }

    /// The usual file extension.
    pub fn extension(self) -> &'static str {
        match self {
            Target::Wgsl => "wgsl",
            Target::Glsl | Target::GlslEs => "frag",
            Target::Hlsl => "hlsl",
            Target::Msl => "metal",
            Target::Spirv => "spv",
        }
    }
}

impl clap::ValueEnum for Target {
    fn value_variants<'a>() -> &'a [Self] {
        const TARGETS: [Target; 6] = [
            Target::ALL[0].0,
            Target::ALL[1].0,
            Target::ALL[2].0,
            Target::ALL[3].0,
            Target::ALL[4].0,
            Target::ALL[5].0,
        ];
        &TARGETS
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        let (_, name, help) = Target::ALL.iter().find(|(target, _, _)| target == self)?;
        Some(clap::builder::PossibleValue::new(*name).help(*help))
    }
}

/// Why an export failed.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The graph does not compile.
    #[error(transparent)]
    Compile(#[from] CompileError),
    /// A back-end (or the check of its output) failed: a bug in Veneer or naga.
    #[error("{target:?} export failed: {message}")]
    Backend { target: Target, message: String },
}

/// The name of the fragment entry point in non-WGSL exports (GLSL calls it `main`).
pub const FRAGMENT_ENTRY: &str = "veneer_fragment";
const ENTRY_SOURCE: &str = include_str!("../../shaders/export_entry.wgsl");

/// The most buffers one exported module binds in GLSL 450 (bindings 2 and up).
const MAX_BUFFER_BINDINGS: u8 = 64;

/// The graph as a shader for `target`, parameters baked or in a uniform block: text for
/// the text languages, bytes for SPIR-V.
pub fn export(graph: &Graph, target: Target, params: ParamMode) -> Result<Vec<u8>, ExportError> {
    let compiled = compile(graph, &CompileOptions::with_params(params))?;
    export_compiled(&compiled, target)
}

/// [`export`] of a graph compiled already (its material module alone: a multi-pass
/// material's passes export through [`super::manifest::export_passes`]).
pub fn export_compiled(compiled: &Compiled, target: Target) -> Result<Vec<u8>, ExportError> {
    let module = &compiled.module;
    if target == Target::Wgsl {
        return Ok(module.source.clone().into_bytes());
    }
    translate(
        &format!("{}\n{ENTRY_SOURCE}", module.source),
        target,
        FRAGMENT_ENTRY,
    )
}

/// A validated WGSL module with entry points (`fragment` the one to export) in
/// `target`'s language.
pub(super) fn translate(
    source: &str,
    target: Target,
    fragment: &str,
) -> Result<Vec<u8>, ExportError> {
    let fail = |message: String| ExportError::Backend { target, message };
    let (naga_module, info) = validated(source).map_err(fail)?;
    match target {
        Target::Wgsl => Ok(source.as_bytes().to_vec()),
        Target::Glsl | Target::GlslEs => {
            let version = if target == Target::Glsl {
                naga::back::glsl::Version::Desktop(450)
            } else {
                naga::back::glsl::Version::Embedded {
                    version: 300,
                    is_webgl: false,
                }
            };
            let text = write_glsl(&naga_module, &info, version, fragment).map_err(fail)?;
            // naga's GLSL front end reads no combined image samplers (a multi-pass
            // material's buffers): glslangValidator checks those in the tests.
            let binds_textures = (naga_module.global_variables.iter()).any(|(_, variable)| {
                matches!(
                    naga_module.types[variable.ty].inner,
                    naga::TypeInner::Image { .. }
                )
            });
            if target == Target::Glsl && !binds_textures {
                check_glsl(&text).map_err(fail)?;
            }
            Ok(text.into_bytes())
        }
        Target::Hlsl => {
            let options = naga::back::hlsl::Options::default();
            let pipeline = naga::back::hlsl::PipelineOptions::default();
            let mut text = String::new();
            let mut writer = naga::back::hlsl::Writer::new(&mut text, &options, &pipeline);
            writer
                .write(&naga_module, &info, None)
                .map_err(|e| fail(e.to_string()))?;
            Ok(text.into_bytes())
        }
        Target::Msl => Ok(write_msl(&naga_module, &info).map_err(fail)?.into_bytes()),
        Target::Spirv => {
            let options = naga::back::spv::Options::default();
            let words = naga::back::spv::write_vec(&naga_module, &info, &options, None)
                .map_err(|e| fail(e.to_string()))?;
            let bytes: Vec<u8> = words.iter().flat_map(|word| word.to_le_bytes()).collect();
            check_spirv(&bytes).map_err(fail)?;
            Ok(bytes)
        }
    }
}

/// `module` as GLSL of `version`, its fragment entry point `entry` the shader's `main`.
/// Explicit bindings where the version has them (450): the frame block at 0, the
/// parameter block at 1, a multi-pass material's buffers (group 2) from 2 on. ES 3.00
/// binds them by name instead.
fn write_glsl(
    module: &naga::Module,
    info: &naga::valid::ModuleInfo,
    version: naga::back::glsl::Version,
    entry: &str,
) -> Result<String, String> {
    let binding = |group, binding| naga::ResourceBinding { group, binding };
    let buffers = (0..MAX_BUFFER_BINDINGS).map(|k| (binding(2, u32::from(k)), 2 + k));
    let binding_map = [(binding(0, 0), 0u8), (binding(1, 0), 1u8)]
        .into_iter()
        .chain(buffers)
        .collect();
    let options = naga::back::glsl::Options {
        version,
        writer_flags: naga::back::glsl::WriterFlags::empty(),
        binding_map,
        ..Default::default()
    };
    let pipeline = naga::back::glsl::PipelineOptions {
        shader_stage: naga::ShaderStage::Fragment,
        entry_point: entry.to_string(),
        multiview: None,
    };
    let mut text = String::new();
    let mut writer = naga::back::glsl::Writer::new(
        &mut text,
        module,
        info,
        &options,
        &pipeline,
        naga::proc::BoundsCheckPolicies::default(),
    )
    .map_err(|e| e.to_string())?;
    writer.write().map_err(|e| e.to_string())?;
    Ok(text)
}

/// `source`, a WGSL module with one fragment entry point, validated and written as GLSL
/// of `version` (MaterialX's node functions: see `bake::materialx`).
pub(crate) fn glsl(source: &str, version: naga::back::glsl::Version) -> Result<String, String> {
    let (module, info) = validated(source)?;
    let entry = (module.entry_points.first())
        .map(|entry| entry.name.clone())
        .ok_or("the module has no entry point")?;
    write_glsl(&module, &info, version, &entry)
}

/// `module` as Metal Shading Language 2.0, bindings it lacks made up.
fn write_msl(module: &naga::Module, info: &naga::valid::ModuleInfo) -> Result<String, String> {
    let options = naga::back::msl::Options {
        lang_version: (2, 0),
        fake_missing_bindings: true,
        ..Default::default()
    };
    let pipeline = naga::back::msl::PipelineOptions::default();
    let (text, _) = naga::back::msl::write_string(module, info, &options, &pipeline)
        .map_err(|e| e.to_string())?;
    Ok(text)
}

/// `source`, a validated WGSL module, written as Metal Shading Language 2.0 (MaterialX's
/// node functions: see `bake::materialx`).
pub(crate) fn msl(source: &str) -> Result<String, String> {
    let (module, info) = validated(source)?;
    write_msl(&module, &info)
}

/// `source` parsed and validated by naga, with what validation found out about it.
fn validated(source: &str) -> Result<(naga::Module, naga::valid::ModuleInfo), String> {
    let module = validate(source).map_err(|error| error.to_string())?;
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|error| error.emit_to_string(source))?;
    Ok((module, info))
}

/// GLSL output parsed back and validated by naga.
fn check_glsl(text: &str) -> Result<(), String> {
    let options = naga::front::glsl::Options::from(naga::ShaderStage::Fragment);
    let module = naga::front::glsl::Frontend::default()
        .parse(&options, text)
        .map_err(|error| {
            format!(
                "the GLSL does not parse back: {}",
                error.emit_to_string(text)
            )
        })?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map(|_| ())
    .map_err(|error| format!("the GLSL does not validate back: {error}"))
}

/// SPIR-V output parsed back and validated by naga.
fn check_spirv(bytes: &[u8]) -> Result<(), String> {
    let module = naga::front::spv::parse_u8_slice(bytes, &naga::front::spv::Options::default())
        .map_err(|error| format!("the SPIR-V does not parse back: {error}"))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map(|_| ())
    .map_err(|error| {
        format!(
            "the SPIR-V does not validate back: {}",
            causes(error.as_inner())
        )
    })
}

/// `error` and every error behind it, joined by colons: naga's validation errors name the
/// function first and say what is wrong with it only in their sources.
fn causes(error: &dyn std::error::Error) -> String {
    let mut text = error.to_string();
    let mut source = error.source();
    while let Some(cause) = source {
        text.push_str(&format!(": {cause}"));
        source = cause.source();
    }
    text
}
