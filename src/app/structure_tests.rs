//! The editor's structure, checked on its source: no file of `src/app` imports another
//! that (through others) imports it back, and no struct has more than
//! [`MAX_FIELDS`] fields (a part with more is split into parts of its own).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The most fields a struct of the editor has.
const MAX_FIELDS: usize = 12;

/// Every `.rs` file under `dir`, with its module path below `crate::app` (`""` for
/// `mod.rs` itself, `canvas::viewer`, `chrome::dialogs` for a folder's `mod.rs`).
fn modules(dir: &Path, prefix: &str, found: &mut BTreeMap<String, PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("src/app is readable")
        .map(|entry| entry.expect("an entry").path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let below = if prefix.is_empty() {
            name.clone()
        } else {
            format!("{prefix}::{name}")
        };
        if path.is_dir() {
            modules(&path, &below, found);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let module = if name == "mod" {
                prefix.to_string()
            } else {
                below
            };
            found.insert(module, path);
        }
    }
}

/// The source of `path` without its test module.
fn code(path: &Path) -> String {
    let text = std::fs::read_to_string(path).expect("a source file");
    match text.find("#[cfg(test)]") {
        Some(at) => text[..at].to_string(),
        None => text,
    }
}

/// The module paths that `code` names after `crate::app::` (braces opened one level).
fn named_paths(code: &str) -> Vec<String> {
    let mut paths = Vec::new();
    for (at, _) in code.match_indices("crate::app::") {
        let rest = &code[at + "crate::app::".len()..];
        let end = rest
            .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':' || c == '{'))
            .unwrap_or(rest.len());
        let path = &rest[..end];
        match path.split_once('{') {
            Some((head, _)) => {
                let inside = rest[head.len() + 1..].split('}').next().unwrap_or("");
                for item in inside.split(',') {
                    let item = item.split_whitespace().next().unwrap_or("");
                    paths.push(format!("{head}{item}"));
                }
            }
            None => paths.push(path.to_string()),
        }
    }
    paths
}

/// The longest module among `modules` that `path` starts with.
fn owner<'a>(path: &str, modules: &'a BTreeMap<String, PathBuf>) -> Option<&'a String> {
    let parts: Vec<&str> = path.split("::").filter(|p| !p.is_empty()).collect();
    (0..=parts.len())
        .rev()
        .find_map(|n| modules.get_key_value(&parts[..n].join("::")))
        .map(|(module, _)| module)
}

/// Which modules each module names.
fn imports() -> BTreeMap<String, BTreeSet<String>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/app");
    let mut found = BTreeMap::new();
    modules(&root, "", &mut found);
    let mut edges = BTreeMap::new();
    for (module, path) in &found {
        let mut code = code(path);
        if module.is_empty() {
            // `mod.rs` names its parts (the top-level modules) without the crate path.
            let parts = found.keys().filter(|m| !m.is_empty() && !m.contains("::"));
            for part in parts {
                code = code.replace(&format!(" {part}::"), &format!(" crate::app::{part}::"));
                code = code.replace(&format!("({part}::"), &format!("(crate::app::{part}::"));
            }
        }
        let named: BTreeSet<String> = named_paths(&code)
            .iter()
            .filter_map(|path| owner(path, &found))
            .filter(|target| *target != module)
            .cloned()
            .collect();
        edges.insert(module.clone(), named);
    }
    edges
}

/// A circle of imports through `start`, if there is one.
fn circle_through(start: &str, edges: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    let mut stack = vec![(start.to_string(), vec![start.to_string()])];
    let mut seen = BTreeSet::new();
    while let Some((module, path)) = stack.pop() {
        for next in edges.get(&module).into_iter().flatten() {
            if next == start {
                return Some(path.clone());
            }
            if seen.insert(next.clone()) {
                let mut longer = path.clone();
                longer.push(next.clone());
                stack.push((next.clone(), longer));
            }
        }
    }
    None
}

#[test]
fn no_file_of_the_editor_imports_another_in_a_circle() {
    let edges = imports();
    assert!(edges.len() > 40, "{} modules found", edges.len());
    for module in edges.keys() {
        if let Some(circle) = circle_through(module, &edges) {
            let shown: Vec<&str> = circle
                .iter()
                .map(|m| if m.is_empty() { "app" } else { m.as_str() })
                .collect();
            panic!("src/app imports in a circle: {} → back", shown.join(" → "));
        }
    }
}

#[test]
fn the_circle_check_finds_a_circle() {
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    edges.insert("a".into(), BTreeSet::from(["b".into()]));
    edges.insert("b".into(), BTreeSet::from(["c".into()]));
    edges.insert("c".into(), BTreeSet::from(["a".into()]));
    assert_eq!(
        circle_through("a", &edges),
        Some(vec!["a".into(), "b".into(), "c".into()])
    );
    let named = named_paths("use crate::app::canvas::{scope, viewer::Viewer};");
    assert_eq!(named, ["canvas::scope", "canvas::viewer::Viewer"]);
}

/// The structs declared in `code`, with how many fields each has.
fn struct_fields(code: &str) -> Vec<(String, usize)> {
    let lines: Vec<&str> = code.lines().collect();
    let mut found = Vec::new();
    let mut index = 0;
    while index < lines.len() {
        let line = lines[index].trim_start();
        let declared = line
            .split_once("struct ")
            .filter(|(before, _)| before.trim().is_empty() || before.trim().starts_with("pub"))
            .map(|(_, after)| after)
            .filter(|after| after.trim_end().ends_with('{'));
        index += 1;
        let Some(after) = declared else {
            continue;
        };
        let name: String = after
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let (mut depth, mut fields) = (1, 0);
        while depth > 0 && index < lines.len() {
            let field = lines[index].trim_start();
            if depth == 1 && !field.starts_with("//") && !field.starts_with('#') {
                let head = field.split(':').next().unwrap_or("");
                let word = head.rsplit(' ').next().unwrap_or("");
                if field.contains(':')
                    && !word.is_empty()
                    && word.chars().all(|c| c.is_alphanumeric() || c == '_')
                {
                    fields += 1;
                }
            }
            depth += field.matches('{').count() as i32 - field.matches('}').count() as i32;
            index += 1;
        }
        found.push((name, fields));
    }
    found
}

#[test]
fn no_struct_of_the_editor_has_more_than_twelve_fields() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/app");
    let mut found = BTreeMap::new();
    modules(&root, "", &mut found);
    let mut large = Vec::new();
    for path in found.values() {
        for (name, fields) in struct_fields(&code(path)) {
            if fields > MAX_FIELDS {
                large.push(format!("{name} ({fields} fields, {})", path.display()));
            }
        }
    }
    assert!(
        large.is_empty(),
        "structs of more than {MAX_FIELDS} fields: {large:?}"
    );
    let sample = "pub struct A {\n    pub a: u8,\n    /// b\n    b: Vec<u8>,\n    c: std::collections::BTreeMap<u8, u8>,\n}\n";
    assert_eq!(struct_fields(sample), [("A".to_string(), 3)]);
}
