//! What each preview slot draws, kept between frames: the material's code (shared until
//! it changes) and its parameter values (worked out again only when the graph changes).

use crate::app::preview::live::LiveMaterial;
use crate::app::preview::state::MaterialFrame;
use crate::graph::Graph;
use crate::render::LiveMaterialCode;
use std::sync::Arc;

/// Set in the generations of field-view materials, so that the preview never mistakes
/// one for the graph's material of the same generation.
pub(in crate::app) const FIELD_VIEW_GENERATIONS: u64 = 1 << 48;

/// Set in the revision of the values a fit tries (the preview's while *Fit to image*
/// runs), so they never share a cache entry with a revision of the document.
pub(in crate::app) const FIT_REVISIONS: u64 = 1 << 62;

/// What a preview's material is made of, kept between frames: the code (shared until
/// it changes) and the parameter values (worked out again only when the graph changes).
#[derive(Default)]
pub(in crate::app) struct FrameCache {
    code: Option<LiveMaterialCode>,
    /// The values, for the code generation and graph revision they were worked out for.
    params: Option<(ParamsKey, Arc<[[f32; 4]]>)>,
}

impl FrameCache {
    /// Whether the code of `generation` was handed to the preview.
    pub fn has_code_of(&self, generation: u64) -> bool {
        self.code
            .as_ref()
            .is_some_and(|code| code.generation == generation)
    }
}

/// A code generation and a graph revision.
type ParamsKey = (u64, u64);

/// What a preview should draw this frame: `live`'s code and its parameter values for
/// `graph` at `revision` (taken from `cache` while neither changed).
pub(in crate::app) fn material_frame(
    live: &LiveMaterial,
    cache: &mut FrameCache,
    graph: &Graph,
    revision: u64,
) -> Option<MaterialFrame> {
    let compiled = live.compiled.as_ref()?;
    if (cache.code.as_ref()).is_none_or(|code| code.generation != live.generation) {
        cache.code = Some(LiveMaterialCode::new(live.generation, compiled));
    }
    let key = (live.generation, revision);
    // While a big graph compiles, the values stay those of the code shown (the slots of
    // the new graph are the new code's).
    let stale = cache.params.as_ref().is_none_or(|(seen, _)| *seen != key);
    let shown_code = cache
        .params
        .as_ref()
        .is_some_and(|((generation, _), _)| *generation == live.generation && live.is_compiling());
    if stale && !shown_code {
        cache.params = Some((key, live.params(graph).into()));
    }
    let code = cache.code.clone()?;
    let params = cache.params.as_ref().map(|(_, params)| params.clone())?;
    Some(MaterialFrame {
        code,
        params,
        tessellation: None,
    })
}
