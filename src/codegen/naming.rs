//! Readable, unique WGSL identifiers for nodes, named after their labels.

use rustc_hash::FxHashSet;
use std::sync::OnceLock;

/// WGSL keywords and reserved words that a label could collide with, plus names the
/// generated function uses itself.
const RESERVED: &[&str] = &[
    "alias",
    "break",
    "case",
    "const",
    "const_assert",
    "continue",
    "continuing",
    "default",
    "diagnostic",
    "discard",
    "else",
    "enable",
    "false",
    "fn",
    "for",
    "if",
    "let",
    "loop",
    "override",
    "requires",
    "return",
    "struct",
    "switch",
    "true",
    "var",
    "while",
    "array",
    "atomic",
    "bool",
    "f16",
    "f32",
    "i32",
    "mat2x2",
    "mat3x3",
    "mat4x4",
    "ptr",
    "sampler",
    "texture",
    "u32",
    "vec2",
    "vec3",
    "vec4",
    "vec2f",
    "vec3f",
    "vec4f",
    "abstract",
    "as",
    "async",
    "await",
    "become",
    "cast",
    "catch",
    "class",
    "co_await",
    "co_return",
    "co_yield",
    "coherent",
    "do",
    "enum",
    "explicit",
    "export",
    "extends",
    "extern",
    "external",
    "final",
    "finally",
    "friend",
    "from",
    "function",
    "fxgroup",
    "get",
    "goto",
    "handle",
    "highp",
    "impl",
    "implements",
    "import",
    "inline",
    "instanceof",
    "interface",
    "layout",
    "lowp",
    "macro",
    "match",
    "mediump",
    "meta",
    "mod",
    "module",
    "move",
    "mut",
    "namespace",
    "new",
    "nil",
    "noexcept",
    "noinline",
    "null",
    "of",
    "operator",
    "package",
    "packoffset",
    "partition",
    "pass",
    "patch",
    "precise",
    "precision",
    "private",
    "protected",
    "public",
    "readonly",
    "ref",
    "resource",
    "restrict",
    "self",
    "set",
    "shared",
    "signed",
    "sizeof",
    "smooth",
    "static",
    "super",
    "target",
    "template",
    "this",
    "throw",
    "trait",
    "try",
    "type",
    "typedef",
    "typeid",
    "typename",
    "typeof",
    "union",
    "unless",
    "unsigned",
    "use",
    "using",
    "varying",
    "virtual",
    "volatile",
    "where",
    "with",
    "writeonly",
    "yield",
    "s",
    "material",
    // Builtin functions: a local of the same name would shadow the builtin.
    "abs",
    "acos",
    "acosh",
    "all",
    "any",
    "asin",
    "asinh",
    "atan",
    "atan2",
    "atanh",
    "bitcast",
    "ceil",
    "clamp",
    "cos",
    "cosh",
    "cross",
    "degrees",
    "determinant",
    "distance",
    "dot",
    "exp",
    "exp2",
    "faceForward",
    "floor",
    "fma",
    "fract",
    "frexp",
    "inverseSqrt",
    "ldexp",
    "length",
    "log",
    "log2",
    "max",
    "min",
    "mix",
    "modf",
    "normalize",
    "pow",
    "radians",
    "reflect",
    "refract",
    "round",
    "saturate",
    "select",
    "sign",
    "sin",
    "sinh",
    "smoothstep",
    "sqrt",
    "step",
    "tan",
    "tanh",
    "transpose",
    "trunc",
];

/// `text` made safe inside a `//` comment: every control character (line breaks above
/// all, which would end the comment and let the rest be read as code) becomes a space.
pub fn comment(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() || matches!(c, '\u{2028}' | '\u{2029}') {
                ' '
            } else {
                c
            }
        })
        .collect()
}

/// Whether `name` is in [`RESERVED`] (a set: a name is looked up for every node).
fn reserved(name: &str) -> bool {
    static SET: OnceLock<FxHashSet<&str>> = OnceLock::new();
    SET.get_or_init(|| RESERVED.iter().copied().collect())
        .contains(name)
}

/// Hands out identifiers, each once.
#[derive(Default)]
pub struct Namer {
    taken: FxHashSet<String>,
}

/// `label` as a snake_case identifier (ASCII letters, digits, underscores).
fn sanitize(label: &str) -> String {
    let mut out = String::new();
    for c in label.chars() {
        if c.is_ascii_alphanumeric() {
            if c.is_ascii_uppercase()
                && out
                    .chars()
                    .last()
                    .is_some_and(|last| last.is_ascii_lowercase())
            {
                out.push('_');
            }
            out.push(c.to_ascii_lowercase());
        } else if !out.is_empty() && !out.ends_with('_') {
            out.push('_');
        }
    }
    let out = out.trim_matches('_').to_string();
    let needs_prefix = out.is_empty()
        || out.starts_with(|c: char| c.is_ascii_digit())
        || out.starts_with("veneer_");
    if needs_prefix {
        if out.is_empty() {
            "n".to_string()
        } else {
            format!("n_{out}")
        }
    } else {
        out
    }
}

impl Namer {
    /// Marks `name` as taken (a function's arguments, before its nodes are named).
    pub fn reserve(&mut self, name: &str) {
        self.taken.insert(name.to_string());
    }

    /// A fresh identifier based on `label`; suffixed with `fallback_id` (then a counter)
    /// when the plain name is reserved or already used.
    pub fn name(&mut self, label: &str, fallback_id: u32) -> String {
        let base = sanitize(label);
        let clashes =
            |name: &str, taken: &FxHashSet<String>| reserved(name) || taken.contains(name);
        let mut name = base.clone();
        if clashes(&name, &self.taken) {
            name = format!("{base}_{fallback_id}");
        }
        let mut counter = 2;
        while clashes(&name, &self.taken) {
            name = format!("{base}_{fallback_id}_{counter}");
            counter += 1;
        }
        self.taken.insert(name.clone());
        name
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_become_unique_snake_case_identifiers() {
        let mut namer = Namer::default();
        assert_eq!(namer.name("Ring Phase", 3), "ring_phase");
        assert_eq!(namer.name("ring phase", 4), "ring_phase_4");
        assert_eq!(namer.name("loop", 5), "loop_5");
        assert_eq!(namer.name("2nd warp", 6), "n_2nd_warp");
        assert_eq!(namer.name("veneer_x", 7), "n_veneer_x");
        assert_eq!(namer.name("", 8), "n");
        assert_eq!(namer.name("grainContrast", 9), "grain_contrast");
    }
}
