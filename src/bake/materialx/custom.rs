//! Veneer's own MaterialX node definitions: a node kind MaterialX's standard library has
//! no equal for (the noises, Worley, the patterns with Veneer's overflow guards) becomes a
//! `nodedef` whose GLSL implementation is the very code Veneer emits for the node, taken
//! through the same WGSL library functions and translated by naga as the GLSL export is —
//! so the pattern MaterialX draws is Veneer's, not MaterialX's differently defined noise.
//!
//! Each definition is one kind with its settings (two Fbm nodes of different octave counts
//! are two definitions); its name carries a digest of the settings, so the same settings
//! make the same definition in every document. The node's code is wrapped in a function
//! taking its input pins in order and writing its outputs through `out` parameters, the
//! calling convention of MaterialX's file-based implementations.

use super::network::{Source, input, node};
use super::standard::Translated;
use crate::nodes::NodeKind;
use crate::nodes::emit::{Detail, Emit};
use crate::nodes::pins::{InputPin, OutputPin, PinDefault};
use crate::nodes::value::ValueType;
use std::fmt::Write;

/// A node kind with its settings as a MaterialX node definition.
#[derive(Clone, Debug, PartialEq)]
pub struct CustomDef {
    /// The node's category in MaterialX (`veneer_fbm_1a2b3c4d`); the definition is
    /// `ND_<category>`, the implementations `IM_<category>_genglsl` and `_genmsl`.
    pub category: String,
    /// The kind, with its settings.
    pub kind: NodeKind,
    pub inputs: Vec<InputPin>,
    pub outputs: Vec<OutputPin>,
    /// The WGSL function the implementations are translated from.
    wrapper: String,
    /// The library items the wrapper calls.
    library: Vec<String>,
}

/// The MaterialX type of a Veneer value type.
pub fn mx_type(ty: ValueType) -> &'static str {
    match ty {
        ValueType::Float => "float",
        ValueType::Vec2 => "vector2",
        ValueType::Vec3 => "vector3",
        ValueType::Color => "color3",
    }
}

/// `name` in snake case (`FractalSum` → `fractal_sum`).
fn snake(name: &str) -> String {
    let mut out = String::new();
    for (k, c) in name.chars().enumerate() {
        if c.is_ascii_uppercase() && k > 0 {
            out.push('_');
        }
        out.push(c.to_ascii_lowercase());
    }
    out
}

/// Why `kind` cannot run as a function of its input pins alone, if it cannot: it reads
/// the surface, a buffer, a bitmap or a local frame.
pub fn unportable(kind: &NodeKind) -> Option<&'static str> {
    let definition = kind.definition();
    let signature = definition.signature();
    if definition.bitmap().is_some() {
        Some("reads a bitmap file")
    } else if signature.inputs.iter().any(|pin| pin.sampled) {
        Some("samples its input around the point (a buffered pass)")
    } else if signature.inputs.iter().any(|pin| pin.re_evaluated) {
        Some("evaluates its input at points of its own (a local frame)")
    } else if definition.reads_surface() {
        Some("reads the surface")
    } else {
        None
    }
}

impl CustomDef {
    /// The definition of `kind` with its settings, or why it has none (see
    /// [`unportable`]; the wrapper must also be valid WGSL on its own).
    pub fn new(kind: &NodeKind) -> Result<CustomDef, String> {
        if let Some(reason) = unportable(kind) {
            return Err(reason.to_string());
        }
        let signature = kind.definition().signature();
        let stem = snake(kind.name());
        let settings = ron::to_string(kind).unwrap_or_default();
        let category = match settings.contains('(') {
            true => format!("veneer_{stem}_{:08x}", crc32fast::hash(settings.as_bytes())),
            false => format!("veneer_{stem}"),
        };
        let arguments: Vec<String> = (signature.inputs.iter())
            .map(|pin| format!("in_{}", pin.name))
            .collect();
        let mut io = Emit::new(
            &signature.inputs,
            &arguments,
            &signature.outputs,
            "node",
            Detail::Full,
        );
        kind.definition().emit(&mut io);
        let code = io.finish();
        let mut parameters: Vec<String> = (signature.inputs.iter())
            .zip(&arguments)
            .map(|(pin, argument)| format!("{argument}: {}", pin.ty.wgsl()))
            .collect();
        parameters.extend(
            (signature.outputs.iter())
                .map(|pin| format!("out_{}: ptr<function, {}>", pin.name, pin.ty.wgsl())),
        );
        let mut wrapper = format!(
            "fn {}({}) {{\n",
            function_name(&category),
            parameters.join(", ")
        );
        for statement in &code.statements {
            let _ = writeln!(wrapper, "    {statement}");
        }
        for (pin, expression) in signature.outputs.iter().zip(&code.outputs) {
            let _ = writeln!(wrapper, "    *out_{} = {expression};", pin.name);
        }
        wrapper.push_str("}\n");
        let definition = CustomDef {
            category,
            kind: kind.clone(),
            inputs: signature.inputs,
            outputs: signature.outputs,
            wrapper,
            library: code.library,
        };
        for language in Language::ALL {
            functions(std::slice::from_ref(&definition), language)?;
        }
        Ok(definition)
    }

    /// The name of output `k` in MaterialX: `out` for the only one, else the pin's name
    /// (with `_out` where an input has it: a definition's elements share one namespace).
    pub fn output_name(&self, k: usize) -> String {
        let name = self.outputs[k].name;
        match self.outputs.len() {
            1 => "out".to_string(),
            _ if self.inputs.iter().any(|pin| pin.name == name) => format!("{name}_out"),
            _ => name.to_string(),
        }
    }

    /// A node `name` of this definition reading `arguments` (one per input pin), and the
    /// sources of its outputs.
    pub fn instance(&self, name: &str, pins: &[InputPin], arguments: Vec<Source>) -> Translated {
        let ty = match self.outputs.as_slice() {
            [one] => mx_type(one.ty),
            _ => "multioutput",
        };
        let inputs = (pins.iter().zip(arguments))
            .map(|(pin, argument)| input(pin.name, mx_type(pin.ty), argument))
            .collect();
        let nodedef = format!("ND_{}", self.category);
        let outputs = match self.outputs.len() {
            1 => vec![Source::Node(name.to_string())],
            count => (0..count)
                .map(|k| Source::Output(name.to_string(), self.output_name(k)))
                .collect(),
        };
        Translated {
            nodes: vec![node(name, &self.category, ty, &nodedef, inputs)],
            outputs,
        }
    }

    /// The function the implementations name.
    pub fn function(&self) -> String {
        function_name(&self.category)
    }

    /// The `<nodedef>` element and one `<implementation>` per language, each reading the
    /// functions from `file(language)` (a file beside the document).
    pub fn xml(&self, file: impl Fn(Language) -> String) -> String {
        let category = &self.category;
        let mut text = format!(
            "  <nodedef name=\"ND_{category}\" node=\"{category}\" nodegroup=\"procedural\" doc=\"{}\">\n",
            super::attribute(&format!(
                "Veneer's {} node: {}",
                self.kind.definition().title(),
                ron::to_string(&self.kind).unwrap_or_default()
            ))
        );
        for pin in &self.inputs {
            let ty = mx_type(pin.ty);
            let default = match &pin.default {
                PinDefault::Const(value) => {
                    format!(
                        " value=\"{}\"",
                        super::value_text(&value.components(), pin.ty)
                    )
                }
                PinDefault::Position => " defaultgeomprop=\"Pobject\"".to_string(),
                PinDefault::Required | PinDefault::Builtin(_) => String::new(),
            };
            let _ = writeln!(
                text,
                "    <input name=\"{}\" type=\"{ty}\"{default} />",
                pin.name
            );
        }
        for (k, pin) in self.outputs.iter().enumerate() {
            let _ = writeln!(
                text,
                "    <output name=\"{}\" type=\"{}\" />",
                self.output_name(k),
                mx_type(pin.ty)
            );
        }
        text.push_str("  </nodedef>\n");
        for language in Language::ALL {
            let target = language.target();
            let _ = writeln!(
                text,
                "  <implementation name=\"IM_{category}_{target}\" nodedef=\"ND_{category}\" target=\"{target}\" file=\"{}\" function=\"{}\" />",
                super::attribute(&file(language)),
                self.function()
            );
        }
        text
    }
}

/// The function of definition `category`: a name naga keeps as it is (none ends in a
/// digit).
fn function_name(category: &str) -> String {
    format!("{category}_node")
}

/// A shading language MaterialX's generators read Veneer's node functions in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Language {
    /// GLSL 4.00, MaterialX's version (`genglsl`).
    Glsl,
    /// Metal Shading Language 2.0 (`genmsl`).
    Msl,
}

impl Language {
    /// Every language a document carries implementations in.
    pub const ALL: [Language; 2] = [Language::Glsl, Language::Msl];

    /// MaterialX's name of the generator target.
    pub fn target(self) -> &'static str {
        match self {
            Language::Glsl => "genglsl",
            Language::Msl => "genmsl",
        }
    }

    /// The extension of the file holding the functions.
    pub fn extension(self) -> &'static str {
        match self {
            Language::Glsl => "glsl",
            Language::Msl => "metal",
        }
    }

    /// The language's name in the file's opening comment.
    fn title(self) -> &'static str {
        match self {
            Language::Glsl => "GLSL 4.00",
            Language::Msl => "Metal Shading Language 2.0",
        }
    }

    /// The module as naga writes it in this language.
    fn translate(self, source: &str) -> Result<String, String> {
        match self {
            Language::Glsl => {
                crate::codegen::export::glsl(source, naga::back::glsl::Version::Desktop(400))
            }
            Language::Msl => crate::codegen::export::msl(source),
        }
    }

    /// Where naga's output of the module starts the entry point, after every function.
    fn entry(self) -> String {
        match self {
            Language::Glsl => "void main()".to_string(),
            Language::Msl => format!("struct {ENTRY}Output"),
        }
    }

    /// Whether a line of naga's output before the entry point belongs to the whole
    /// shader rather than the functions (the version, includes, namespace, the stage's
    /// output).
    fn is_preamble(self, line: &str) -> bool {
        match self {
            Language::Glsl => line.starts_with('#') || line.starts_with("layout("),
            Language::Msl => {
                line.starts_with('#') || line.starts_with("using ") || line.starts_with("//")
            }
        }
    }
}

/// The file of `definitions` in `language`: their functions and every library function
/// they call, translated from WGSL by naga, inside one include guard named after the
/// text's digest, so MaterialX may paste it once per definition and a shader still
/// holds each function once.
pub fn functions(definitions: &[CustomDef], language: Language) -> Result<String, String> {
    let roots = definitions.iter().flat_map(|d| d.library.iter());
    let mut source = String::new();
    for item in crate::codegen::library::closure(roots.map(String::as_str)) {
        source.push_str(&item.text);
        source.push('\n');
    }
    for definition in definitions {
        source.push_str(&definition.wrapper);
        source.push('\n');
    }
    // naga writes the functions its entry point reaches: the entry calls each once.
    let _ = writeln!(source, "@fragment\nfn {ENTRY}() -> @location(0) vec4f {{");
    for (k, definition) in definitions.iter().enumerate() {
        let mut arguments: Vec<String> = (definition.inputs.iter())
            .map(|pin| format!("{}()", pin.ty.wgsl()))
            .collect();
        for (j, pin) in definition.outputs.iter().enumerate() {
            let _ = writeln!(source, "    var out_{k}_{j}: {};", pin.ty.wgsl());
            arguments.push(format!("&out_{k}_{j}"));
        }
        let _ = writeln!(
            source,
            "    {}({});",
            definition.function(),
            arguments.join(", ")
        );
    }
    source.push_str("    return vec4f(0.0);\n}\n");
    let text = (language.translate(&source)).map_err(|error| {
        format!(
            "its code does not translate to {}: {error}",
            language.title()
        )
    })?;
    // naga writes a whole shader: keep its structs and functions, not what belongs to
    // the shader (see `is_preamble`) or the entry point.
    let end = text.find(&language.entry()).unwrap_or(text.len());
    let body: String = text[..end]
        .lines()
        .filter(|line| !language.is_preamble(line))
        .map(|line| format!("{line}\n"))
        .collect();
    for definition in definitions {
        if !body.contains(&format!("void {}(", definition.function())) {
            return Err(format!(
                "naga renamed the function of {}",
                definition.category
            ));
        }
    }
    let guard = format!("VENEER_{:08X}", crc32fast::hash(body.as_bytes()));
    Ok(format!(
        "// Veneer's node functions for MaterialX ({}), translated from its WGSL by naga.\n#ifndef {guard}\n#define {guard}\n{}#endif\n",
        language.title(),
        body.trim_start_matches('\n')
    ))
}

/// The entry point through which naga reaches the functions.
const ENTRY: &str = "veneer_materialx_entry";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_portable_kind_translates_and_settings_name_the_definition() {
        let mut categories = std::collections::BTreeSet::new();
        for kind in NodeKind::examples() {
            if unportable(&kind).is_some() {
                continue;
            }
            let definition =
                CustomDef::new(&kind).unwrap_or_else(|e| panic!("{}: {e}", kind.name()));
            categories.insert(definition.category.clone());
            for language in Language::ALL {
                let text = functions(std::slice::from_ref(&definition), language).unwrap();
                assert!(text.contains(&format!("void {}(", definition.function())));
                if kind.name() == "Worley" && std::env::var_os("VENEER_SHOW_FUNCTIONS").is_some() {
                    println!("{text}");
                }
            }
        }
        assert!(categories.len() > 20, "{categories:?}");
    }
}
