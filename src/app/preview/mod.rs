//! The live preview: the compiled material, its drawing thread, the mesh's distance
//! fields, the selected node's probe, and the panel that shows them.

pub(in crate::app) mod background;
pub(in crate::app) mod drawing_thread;
pub(in crate::app) mod fields;
pub(in crate::app) mod frame_cache;
pub(in crate::app) mod live;
pub(in crate::app) mod panel;
pub(in crate::app) mod probe;
pub(in crate::app) mod state;
pub(in crate::app) mod worker;

use crate::app::preview::frame_cache::FrameCache;
use crate::app::preview::live::LiveMaterial;
use crate::graph::Graph;
use std::sync::Arc;

/// The preview's state: the compiled materials, the pictures drawn of them on another
/// thread, the mesh's distance fields and the selected node's probe.
pub(in crate::app) struct Preview {
    /// The graph's material, compiled and linted.
    pub live: LiveMaterial,
    /// The selected node's output, compiled for its thumbnail.
    pub thumbnail: LiveMaterial,
    /// The mesh, camera, light and time the preview shows.
    pub state: state::PreviewState,
    /// The pictures of the preview and of the selected node, drawn on another thread.
    pub previews: state::Previews,
    /// The material handed to each preview slot (main, node), kept between frames.
    pub frames: [FrameCache; worker::Slot::ALL.len()],
    /// The selected node's output as a graph of its own, for the graph revision, node
    /// and square (the unit tile or not) it was made for.
    pub probe: Option<((u64, crate::graph::NodeId, bool), Option<Graph>)>,
    /// The preview mesh's distance fields: solving, picking sources, viewing.
    pub fields: fields::FieldState,
    /// The field view's material (a colour scale with isolines of one field).
    pub field_view: LiveMaterial,
    pub field_view_frame: FrameCache,
    /// The graph checked at a revision, for refining a displaced preview mesh.
    pub tessellation_graph: Option<(u64, Arc<crate::graph::CheckedGraph>)>,
    pub render_state: Option<eframe::egui_wgpu::RenderState>,
}

impl Preview {
    /// A preview set up as `settings` say, drawing through `render_state` (none: no GPU).
    pub fn new(
        ctx: &egui::Context,
        settings: &crate::graph::Preview,
        render_state: Option<eframe::egui_wgpu::RenderState>,
    ) -> Preview {
        Preview {
            live: LiveMaterial::in_background(ctx),
            thumbnail: LiveMaterial::in_storage(),
            state: state::PreviewState::for_graph(settings),
            previews: state::Previews::new(ctx, render_state.is_some()),
            frames: Default::default(),
            probe: None,
            fields: Default::default(),
            field_view: LiveMaterial::in_storage(),
            field_view_frame: FrameCache::default(),
            tessellation_graph: None,
            render_state,
        }
    }
}
