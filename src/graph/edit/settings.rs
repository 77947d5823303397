//! The graph's settings (name, preview, alpha, shading, comment frames) and a group's
//! link to the library.

use super::{Applied, Change, EditError, GraphEdit, GraphSetting};
use crate::graph::Graph;

/// Sets one of the graph's settings.
pub(super) fn set(graph: &mut Graph, setting: GraphSetting) -> Applied {
    fn swap<T: PartialEq>(place: &mut T, value: T) -> (T, bool) {
        let old = std::mem::replace(place, value);
        let changed = old != *place;
        (old, changed)
    }
    let (old, changed, change) = match setting {
        GraphSetting::Name(name) => {
            let (old, changed) = swap(&mut graph.name, name);
            (GraphSetting::Name(old), changed, Change::Settings)
        }
        GraphSetting::Preview(preview) => {
            let (old, changed) = swap(&mut graph.preview, preview);
            (GraphSetting::Preview(old), changed, Change::Settings)
        }
        GraphSetting::Alpha(alpha) => {
            let (old, changed) = swap(&mut graph.alpha, alpha);
            (GraphSetting::Alpha(old), changed, Change::Settings)
        }
        GraphSetting::Shading(shading) => {
            let (old, changed) = swap(&mut graph.shading, shading);
            (GraphSetting::Shading(old), changed, Change::Settings)
        }
        GraphSetting::Frames(frames) => {
            let (old, changed) = swap(&mut graph.frames, frames);
            (GraphSetting::Frames(old), changed, Change::Layout)
        }
    };
    let inverse = GraphEdit::Set(old);
    Applied::when(changed, inverse, change)
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
