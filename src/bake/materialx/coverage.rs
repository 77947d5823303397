//! The procedural tier's coverage: how each node kind of the registry reaches MaterialX,
//! as the README's table (generated from the same routing the export uses, by a test, so
//! it cannot drift).

use super::procedural::{Route, route};
use crate::nodes::NodeKind;
use std::fmt::Write;

/// The table (Markdown) of every node kind and how its settings translate, after a line
/// of counts.
pub fn coverage_table() -> String {
    let examples = NodeKind::examples();
    let mut rows = String::new();
    let (mut standard, mut own, mut mixed, mut textures, mut untranslated) = (0, 0, 0, 0, 0);
    for name in NodeKind::NAMES {
        let kinds: Vec<&NodeKind> = examples.iter().filter(|k| k.name() == *name).collect();
        let routes: Vec<Route> = kinds.iter().map(|kind| route(kind)).collect();
        let count = |test: fn(&Route) -> bool| routes.iter().filter(|r| test(r)).count();
        let standards = count(|r| matches!(r, Route::Standard));
        let definitions = count(|r| matches!(r, Route::Definition(_)));
        // The settings of the kinds a route takes, as graph files write them.
        let settings = |test: fn(&Route) -> bool| {
            let settings: std::collections::BTreeSet<String> = (kinds.iter().zip(&routes))
                .filter(|(_, r)| test(r))
                .map(|(kind, _)| {
                    let text = ron::to_string(kind).unwrap_or_default();
                    let inner = text.split_once('(').map_or("", |(_, inner)| inner);
                    format!("`{}`", inner.trim_end_matches(')').replace(',', ", "))
                })
                .collect();
            settings.into_iter().collect::<Vec<_>>().join("; ")
        };
        let structural = match *name {
            "Material" => Some("the surface shader's inputs (see above)"),
            "Group" => Some(
                "a node definition of its own (`ND_veneer_group_<name>`, its inputs and outputs the group's) implemented by a node graph of the group's nodes, translated one by one; groups nested in it are inlined into that node graph",
            ),
            "GraphBake" => Some("expanded into a Buffer node before translation (not translated)"),
            _ => None,
        };
        if let Some(how) = structural {
            let _ = writeln!(rows, "| `{name}` | {how} |");
            continue;
        }
        let how = match routes.first() {
            _ if standards == routes.len() => {
                standard += 1;
                "standard nodes".to_string()
            }
            _ if definitions == routes.len() => {
                own += 1;
                "Veneer's own definition".to_string()
            }
            _ if standards + definitions == routes.len() => {
                mixed += 1;
                let own = settings(|r| matches!(r, Route::Definition(_)));
                format!("standard nodes; Veneer's own definition for {own}")
            }
            Some(Route::Bitmap(_)) => {
                textures += 1;
                "`image` node reading the bitmap, written beside the document".to_string()
            }
            Some(Route::Texture) => {
                textures += 1;
                "`image` node reading the field baked over the preview mesh's UV layout".to_string()
            }
            Some(Route::None(reason)) => {
                untranslated += 1;
                format!("not translated: {reason}")
            }
            _ => unreachable!("every kind has examples"),
        };
        let _ = writeln!(rows, "| `{name}` | {how} |");
    }
    let total = standard + mixed + own + textures + untranslated;
    format!(
        "Of {total} node kinds (besides the material output, groups and graph bakes), {standard} translate to MaterialX's standard nodes, {mixed} to standard nodes for some settings and to Veneer's own definitions for the rest, {own} to Veneer's own definitions, {textures} to `image` nodes reading textures written beside the document, and {untranslated} do not translate (`--tier auto` reads what they give from textures baked beside).\n\n| Node kind | In MaterialX |\n|---|---|\n{rows}"
    )
}
