//! The WGSL function library in `shaders/`: parsing it into items, instantiating
//! templates, and selecting exactly the items a material needs, in dependency order.

use std::collections::BTreeSet;
use std::sync::OnceLock;

/// The library sources, one family per file.
const SOURCES: [(&str, &str); 25] = [
    ("hash", include_str!("../../shaders/hash.wgsl")),
    ("value", include_str!("../../shaders/value.wgsl")),
    ("gradient", include_str!("../../shaders/gradient.wgsl")),
    ("simplex", include_str!("../../shaders/simplex.wgsl")),
    ("fractal", include_str!("../../shaders/fractal.wgsl")),
    ("worley", include_str!("../../shaders/worley.wgsl")),
    ("coords", include_str!("../../shaders/coords.wgsl")),
    ("patterns", include_str!("../../shaders/patterns.wgsl")),
    ("band_limit", include_str!("../../shaders/band_limit.wgsl")),
    ("instances", include_str!("../../shaders/instances.wgsl")),
    ("shapes", include_str!("../../shaders/shapes.wgsl")),
    ("math", include_str!("../../shaders/math.wgsl")),
    ("fields", include_str!("../../shaders/fields.wgsl")),
    ("white", include_str!("../../shaders/white.wgsl")),
    (
        "value_gradient",
        include_str!("../../shaders/value_gradient.wgsl"),
    ),
    ("gabor", include_str!("../../shaders/gabor.wgsl")),
    (
        "fractal_rotated",
        include_str!("../../shaders/fractal_rotated.wgsl"),
    ),
    (
        "worley_edge",
        include_str!("../../shaders/worley_edge.wgsl"),
    ),
    ("colour", include_str!("../../shaders/colour.wgsl")),
    ("map_range", include_str!("../../shaders/map_range.wgsl")),
    ("buffers", include_str!("../../shaders/buffers.wgsl")),
    ("image_ops", include_str!("../../shaders/image_ops.wgsl")),
    ("jump_flood", include_str!("../../shaders/jump_flood.wgsl")),
    ("flood_fill", include_str!("../../shaders/flood_fill.wgsl")),
    ("reduce", include_str!("../../shaders/reduce.wgsl")),
];

/// The contract structs every exported module starts with.
pub const SURFACE: &str = include_str!("../../shaders/surface.wgsl");

/// Template placeholders and the values each may take.
const PLACEHOLDERS: [(&str, &[&str]); 5] = [
    ("TYPE", &["f32", "vec2f", "vec3f"]),
    ("CELLS", &["worley", "worley_simplex"]),
    ("HASH", &["sine", "pcg"]),
    ("BASIS", &["value_sine", "value_pcg", "gradient", "simplex"]),
    ("MODE", &["fbm", "turbulence", "fractal_sum"]),
];

/// One top-level item (function or struct) of a library file, possibly a template.
#[derive(Debug)]
struct Item {
    /// Name as written, placeholders included (`veneer_safe_div_TYPE`).
    name: String,
    /// The item's text with its leading comment.
    text: String,
    family: &'static str,
}

/// A concrete library item ready to emit.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    pub name: String,
    pub text: String,
    pub family: &'static str,
}

fn parse(family: &'static str, source: &str) -> Vec<Item> {
    let mut items = Vec::new();
    let mut comment = String::new();
    let mut current: Option<(String, String)> = None;
    for line in source.lines() {
        if let Some((name, text)) = current.as_mut() {
            text.push_str(line);
            text.push('\n');
            if line == "}" {
                items.push(Item {
                    name: std::mem::take(name),
                    text: std::mem::take(text),
                    family,
                });
                current = None;
            }
            continue;
        }
        let header = line
            .strip_prefix("fn ")
            .or_else(|| line.strip_prefix("struct "));
        match header {
            Some(rest) => {
                let name: String = rest
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                current = Some((name, std::mem::take(&mut comment) + line + "\n"));
            }
            None if line.starts_with("//!") => {}
            None if line.starts_with("//") => {
                comment.push_str(line);
                comment.push('\n');
            }
            None => comment.clear(),
        }
    }
    items
}

fn items() -> &'static [Item] {
    static ITEMS: OnceLock<Vec<Item>> = OnceLock::new();
    ITEMS.get_or_init(|| {
        SOURCES
            .iter()
            .flat_map(|(family, source)| parse(family, source))
            .collect()
    })
}

/// Every substitution of the placeholders that occur in `template`'s name.
fn substitutions(template: &str) -> Vec<Vec<(&'static str, &'static str)>> {
    let mut all = vec![vec![]];
    for (placeholder, values) in PLACEHOLDERS {
        if !template.contains(placeholder) {
            continue;
        }
        all = all
            .into_iter()
            .flat_map(|partial: Vec<(&str, &str)>| {
                values.iter().map(move |value| {
                    let mut next = partial.clone();
                    next.push((placeholder, *value));
                    next
                })
            })
            .collect();
    }
    all
}

fn apply(text: &str, substitution: &[(&str, &str)]) -> String {
    substitution
        .iter()
        .fold(text.to_string(), |text, (placeholder, value)| {
            text.replace(placeholder, value)
        })
}

/// The library item called `name`, instantiating a template when needed.
pub fn instance(name: &str) -> Option<Instance> {
    items().iter().find_map(|item| {
        let substitution = substitutions(&item.name)
            .into_iter()
            .find(|s| apply(&item.name, s) == name)?;
        Some(Instance {
            name: name.to_string(),
            text: apply(&item.text, &substitution),
            family: item.family,
        })
    })
}

/// Identifiers starting with `veneer_` that `text` mentions.
fn veneer_identifiers(text: &str) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let bytes = text.as_bytes();
    let mut start = 0;
    while let Some(offset) = text[start..].find("veneer_") {
        let begin = start + offset;
        let preceded =
            begin > 0 && (bytes[begin - 1].is_ascii_alphanumeric() || bytes[begin - 1] == b'_');
        let end = begin
            + text[begin..]
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(text.len() - begin);
        if !preceded {
            found.insert(text[begin..end].to_string());
        }
        start = end;
    }
    found
}

/// The items needed by `roots` (library item names), dependencies first, each once.
///
/// Panics if a root or a dependency is missing: the library is part of the program,
/// so a missing item is a bug in Veneer, not in the user's graph.
pub fn closure<'a>(roots: impl IntoIterator<Item = &'a str>) -> Vec<Instance> {
    fn visit(name: &str, seen: &mut BTreeSet<String>, out: &mut Vec<Instance>) {
        if !seen.insert(name.to_string()) {
            return;
        }
        let item = instance(name).unwrap_or_else(|| panic!("WGSL library has no item '{name}'"));
        for dependency in veneer_identifiers(&item.text) {
            if dependency != name && instance(&dependency).is_some() {
                visit(&dependency, seen, out);
            }
        }
        out.push(item);
    }
    let mut seen = BTreeSet::new();
    let mut out = Vec::new();
    for root in roots {
        visit(root, &mut seen, &mut out);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn templates_instantiate_with_their_dependencies_first() {
        let items = closure(["veneer_fbm_value_sine"]);
        let names: Vec<&str> = items.iter().map(|i| i.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "veneer_lattice_domain",
                "veneer_lattice_sine",
                "veneer_noise_value_sine",
                "veneer_octave_fbm_value_sine",
                "veneer_octave_mean_fbm",
                "veneer_fbm_value_sine"
            ]
        );
        assert!(!items[5].text.contains("BASIS") && !items[5].text.contains("MODE"));
    }

    #[test]
    fn unknown_names_are_not_items() {
        assert!(instance("veneer_noise_value_md5").is_none());
        assert!(instance("veneer_safe_div_vec4f").is_none());
        assert!(instance("veneer_safe_div_vec3f").is_some());
    }
}
