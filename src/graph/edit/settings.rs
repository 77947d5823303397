//! The graph's settings (name, preview, alpha, shading, comment frames) and a group's
//! link to the library.

use super::{Applied, Change, EditError, GraphEdit, GraphSetting};
use crate::graph::Graph;

/// Sets one of the graph's settings.
pub(super) fn set(graph: &mut Graph, setting: GraphSetting) -> Applied {
    let old = read(graph, &setting);
    let changed = old != setting;
    let change = match setting {
        GraphSetting::Frames(_) => Change::Layout,
        _ => Change::Settings,
    };
    write(graph, setting);
    Applied::when(changed, GraphEdit::Set(old), change)
}

/// The graph's value of the setting `like` is.
fn read(graph: &Graph, like: &GraphSetting) -> GraphSetting {
    match like {
        GraphSetting::Name(_) => GraphSetting::Name(graph.name.clone()),
        GraphSetting::Preview(_) => GraphSetting::Preview(graph.preview.clone()),
        GraphSetting::Alpha(_) => GraphSetting::Alpha(graph.alpha),
        GraphSetting::Shading(_) => GraphSetting::Shading(graph.shading),
        GraphSetting::Frames(_) => GraphSetting::Frames(graph.frames.clone()),
    }
}

/// Puts `setting` in the graph.
fn write(graph: &mut Graph, setting: GraphSetting) {
    match setting {
        GraphSetting::Name(name) => graph.name = name,
        GraphSetting::Preview(preview) => graph.preview = preview,
        GraphSetting::Alpha(alpha) => graph.alpha = alpha,
        GraphSetting::Shading(shading) => graph.shading = shading,
        GraphSetting::Frames(frames) => graph.frames = frames,
    }
}

/// Links group `group` to the library, or makes it local.
pub(super) fn set_linked(
    graph: &mut Graph,
    group: String,
    linked: bool,
) -> Result<Applied, EditError> {
    let definition = graph
        .groups
        .get_mut(&group)
        .ok_or_else(|| EditError::UnknownGroup(group.clone()))?;
    let old = std::mem::replace(&mut definition.linked, linked);
    let inverse = GraphEdit::SetLinked { group, linked: old };
    Ok(Applied::when(old != linked, inverse, Change::Settings))
}
