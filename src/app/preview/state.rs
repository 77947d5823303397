//! The preview panel's picture: the live material on a mesh (or flat, unlit, from above)
//! and the selected node's output, drawn by the preview thread
//! ([`crate::app::preview::worker`]) and shown as egui textures. Each mesh (and the flat view)
//! keeps its own camera; while anything is dragged the preview draws drafts, and refines
//! when the pointer is let go.

use crate::app::preview::worker::{
    EnvironmentChoice, MeshChoice, Request, Slot, TessellationInput, Worker,
};
use crate::graph::Preview;
use crate::nodes::mesh_field::MeshLanes;
use crate::render::{LiveMaterialCode, MeshView, Projection, Quality};
use egui::{Sense, TextureHandle, TextureOptions, Ui};
use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

/// Where a camera looks from: orbit angles, distance and target.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Camera {
    yaw: f32,
    pitch: f32,
    distance: f32,
    target: [f32; 3],
}

impl Camera {
    fn of(view: &MeshView) -> Camera {
        Camera {
            yaw: view.yaw,
            pitch: view.pitch,
            distance: view.distance,
            target: view.target,
        }
    }

    fn apply(self, view: &mut MeshView) {
        view.yaw = self.yaw;
        view.pitch = self.pitch;
        view.distance = self.distance;
        view.target = self.target;
    }
}

/// The camera every mesh starts with, and a reset returns to.
fn default_camera() -> Camera {
    Camera::of(&MeshView::for_preview(&Preview::default()))
}

/// What the preview shows and from where; kept by the app between frames.
pub struct PreviewState {
    /// A primitive's name or a mesh file's path.
    pub mesh: String,
    /// The loaded mesh when `mesh` is a file (fitted to the unit sphere).
    pub file: Option<Arc<crate::mesh::Mesh>>,
    /// The mesh with its distance fields solved, and what it was solved for; drawn in
    /// place of the plain mesh when present.
    pub prepared: Option<(String, Arc<crate::mesh::Mesh>)>,
    pub view: MeshView,
    /// The environment lighting metallic-roughness materials (the sky until one is
    /// opened).
    pub environment: EnvironmentChoice,
    /// Show the albedo flat from above instead of lit on the mesh.
    pub flat: bool,
    /// In the flat view: show the unit tile 3×3 times, as a bake of it repeats.
    pub repeat_tile: bool,
    pub playing: bool,
    /// The cameras of the meshes (and of the flat view) not shown now.
    cameras: BTreeMap<String, Camera>,
    /// Whose camera `view` holds.
    camera_of: String,
    /// When time last advanced, while playing.
    last_tick: Option<Instant>,
}

/// The flat view's key among the cameras.
const FLAT_CAMERA: &str = "\u{0}flat";

impl PreviewState {
    /// The default preview of a graph.
    pub fn for_graph(preview: &Preview) -> PreviewState {
        PreviewState {
            file: None,
            prepared: None,
            mesh: preview.mesh.clone(),
            view: MeshView::for_preview(preview),
            environment: EnvironmentChoice::default(),
            flat: false,
            repeat_tile: false,
            playing: false,
            cameras: BTreeMap::new(),
            camera_of: preview.mesh.clone(),
            last_tick: None,
        }
    }

    /// The mesh shown, without distance fields: the primitive named (made anew) or the
    /// loaded file.
    pub fn plain_mesh(&self) -> Option<Arc<crate::mesh::Mesh>> {
        crate::mesh::primitive(&self.mesh)
            .map(Arc::new)
            .or_else(|| self.file.clone())
    }

    /// Takes the placement (centre and size in texture space) of `preview` for a graph
    /// just opened: the time starts again from 0, paused, every camera resets, and the
    /// lighting is the default again.
    pub fn follow(&mut self, preview: &Preview) {
        // Lighting, exposure, tone mapping and the environment start afresh with each
        // graph: what suited the last one is not carried into the next.
        self.view = MeshView::for_preview(preview);
        self.environment = EnvironmentChoice::default();
        self.playing = false;
        self.last_tick = None;
        self.cameras.clear();
        default_camera().apply(&mut self.view);
    }

    /// How a render of the preview shows its material: the preview's lighting,
    /// environment, exposure and tone mapping.
    pub fn look(&self) -> crate::render::MeshLook {
        crate::render::MeshLook {
            tone_map: self.view.tone_map,
            exposure: self.view.exposure,
            environment: self.environment.0.clone(),
            environment_turn: self.view.environment_turn,
            key_light: self.view.key_light,
            backdrop: self.view.backdrop,
            ..crate::render::MeshLook::default()
        }
    }

    /// Puts the camera of what is shown back where it starts.
    pub fn reset_camera(&mut self) {
        default_camera().apply(&mut self.view);
    }

    /// Whose camera the view should hold now: the flat view's or the mesh's.
    fn camera_key(&self) -> String {
        if self.flat {
            FLAT_CAMERA.to_string()
        } else {
            self.mesh.clone()
        }
    }

    /// Swaps cameras when the mesh or the flat view changed: each keeps its own, so a
    /// zoom on one mesh does not crop the next.
    fn switch_camera(&mut self) {
        let key = self.camera_key();
        if key == self.camera_of {
            return;
        }
        let old = std::mem::replace(&mut self.camera_of, key.clone());
        self.cameras.insert(old, Camera::of(&self.view));
        self.cameras
            .remove(&key)
            .unwrap_or_else(default_camera)
            .apply(&mut self.view);
    }

    /// Advances time while playing, by the wall-clock time since the last frame (`now`),
    /// so animations run in real time whatever the frame rate; after a stall of over a
    /// quarter second time goes on from where it was.
    pub fn tick(&mut self, now: Instant) {
        if !self.playing {
            self.last_tick = None;
            return;
        }
        let dt = self.last_tick.map_or(0.0, |last| {
            now.saturating_duration_since(last).as_secs_f32().min(0.25)
        });
        self.last_tick = Some(now);
        self.view.time = (self.view.time + dt) % 20.0;
    }

    /// The mesh to draw: the solved one, the loaded file, or a primitive by name; flat,
    /// the plane, its vertices carrying what a flat plane gives in the mesh-field
    /// `lanes` of the material drawn.
    fn mesh_choice(&self, lanes: &MeshLanes) -> MeshChoice {
        if self.flat {
            let fields = crate::nodes::mesh_field::flat_fields(lanes);
            if fields == [0.0; 4] {
                return MeshChoice {
                    key: "plane".into(),
                    mesh: None,
                };
            }
            let mut plane = crate::mesh::primitive("plane").expect("the plane exists");
            plane.fields = vec![fields; plane.positions.len()];
            return MeshChoice {
                key: format!("plane with fields {fields:?}"),
                mesh: Some(Arc::new(plane)),
            };
        }
        match (&self.prepared, &self.file) {
            (Some((key, mesh)), _) => MeshChoice {
                key: key.clone(),
                mesh: Some(Arc::clone(mesh)),
            },
            // A file is kept only while `mesh` names it.
            (None, Some(file)) => MeshChoice {
                key: self.mesh.clone(),
                mesh: Some(Arc::clone(file)),
            },
            _ => MeshChoice {
                key: self.mesh.clone(),
                mesh: None,
            },
        }
    }

    /// The view as drawn: the flat view looks straight down, unlit.
    fn frame_view(&self) -> MeshView {
        let mut view = self.view.clone();
        if self.flat {
            view.projection = Projection::TopDown {
                extent: self.view.distance / 3.6,
            };
            view.unlit = true;
            view.repeat_tile = self.repeat_tile;
        }
        view
    }
}

/// The material a preview draws: its code and its parameter values.
#[derive(Clone)]
pub struct MaterialFrame {
    pub code: LiveMaterialCode,
    pub params: Arc<[[f32; 4]]>,
    /// What refining a displaced mesh for the view needs, when the graph asks for it.
    pub tessellation: Option<TessellationInput>,
}

/// One preview's picture on the UI side: the newest image drawn and what was asked.
#[derive(Default)]
struct Shown {
    texture: Option<TextureHandle>,
    /// The last request posted and its number.
    posted: Option<(u64, Request)>,
    /// The number of the request whose image is shown, and how finely it was drawn.
    shown: u64,
    quality: Option<Quality>,
    /// The shown image's width in pixels and how long it took to draw.
    drawn: Option<(usize, std::time::Duration)>,
    /// Why the newest request could not be drawn (the previous image stays).
    error: Option<String>,
    materials_built: u64,
}

/// The previews (see [`Slot`]), drawn by one thread with its own device.
pub struct Previews {
    worker: Option<Worker>,
    shown: [Shown; Slot::ALL.len()],
    next_id: u64,
    /// Pictures of requests numbered below this were forgotten: one still being drawn
    /// is dropped when it arrives.
    forgotten_below: u64,
}

impl Previews {
    /// The previews, drawing through a thread of their own when there is a GPU (the
    /// editor's window has a wgpu renderer).
    pub fn new(ctx: &egui::Context, gpu: bool) -> Previews {
        let wake = ctx.clone();
        Previews {
            worker: gpu.then(|| Worker::start(move || wake.request_repaint())),
            shown: Default::default(),
            next_id: 1,
            forgotten_below: 0,
        }
    }

    /// Whether previews are drawn at all.
    pub fn available(&self) -> bool {
        self.worker.is_some()
    }

    /// Takes the frames drawn since the last call into the textures.
    pub fn receive(&mut self, ctx: &egui::Context) {
        let Some(worker) = &self.worker else {
            return;
        };
        for drawn in worker.drawn() {
            if drawn.id < self.forgotten_below {
                continue;
            }
            let shown = &mut self.shown[drawn.slot as usize];
            shown.materials_built = drawn.materials_built;
            shown.shown = shown.shown.max(drawn.id);
            match drawn.image {
                Ok(image) => {
                    shown.error = None;
                    shown.quality = Some(drawn.quality);
                    shown.drawn = Some((image.width(), drawn.took));
                    match &mut shown.texture {
                        Some(texture) => texture.set(image, TextureOptions::LINEAR),
                        None => {
                            let name = format!("preview {:?}", drawn.slot);
                            shown.texture =
                                Some(ctx.load_texture(name, image, TextureOptions::LINEAR));
                        }
                    }
                }
                Err(error) => shown.error = Some(error),
            }
        }
    }

    /// Drops every preview's picture, and any being drawn: the background shows until
    /// the next is drawn.
    pub fn forget(&mut self) {
        self.shown = Default::default();
        self.forgotten_below = self.next_id;
    }

    /// Posts `request` for `slot` unless what was posted last already shows it.
    fn post(&mut self, slot: Slot, request: Request) {
        let Some(worker) = &self.worker else {
            return;
        };
        let shown = &mut self.shown[slot as usize];
        if shown
            .posted
            .as_ref()
            .is_some_and(|(_, posted)| request.shown_by(posted))
        {
            return;
        }
        let id = self.next_id;
        self.next_id += 1;
        shown.posted = Some((id, request.clone()));
        worker.post(slot, id, request);
    }

    /// Whether every preview shows, at full quality, the last thing asked of it.
    pub fn settled(&self) -> bool {
        self.shown.iter().all(|shown| match &shown.posted {
            None => true,
            Some((id, request)) => shown.shown >= *id && request.quality == Quality::Full,
        })
    }

    /// Materials the main preview has built pipelines for.
    pub fn materials_built(&self) -> u64 {
        self.shown[Slot::Main as usize].materials_built
    }

    /// How finely the main preview's image on screen was drawn (`None`: no image yet).
    pub fn quality(&self) -> Option<Quality> {
        self.shown[Slot::Main as usize].quality
    }

    /// Why the main preview could not draw its newest material, if it could not.
    pub fn error(&self) -> Option<&str> {
        self.shown[Slot::Main as usize].error.as_deref()
    }

    /// Draws the newest picture of `slot` into `rect` (the background until there is one);
    /// a draft of the material says how coarse it is and what it took.
    fn paint(&self, ui: &Ui, slot: Slot, rect: egui::Rect, background: [f32; 3]) {
        let shown = &self.shown[slot as usize];
        match &shown.texture {
            Some(texture) => {
                let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
                ui.painter()
                    .image(texture.id(), rect, uv, egui::Color32::WHITE);
                // The node's small output picture would be covered by the note.
                if let (Slot::Main, Some(Quality::Draft), Some((width, took))) =
                    (slot, shown.quality, shown.drawn)
                {
                    let pixels = rect.width() * ui.ctx().pixels_per_point();
                    let note = draft_note(pixels, width, took);
                    ui.painter().text(
                        rect.left_bottom() + egui::vec2(6.0, -6.0),
                        egui::Align2::LEFT_BOTTOM,
                        note,
                        egui::FontId::proportional(11.0),
                        ui.visuals().weak_text_color(),
                    );
                }
            }
            None => {
                let [r, g, b] = background;
                let colour = egui::Rgba::from_rgb(r, g, b);
                ui.painter().rect_filled(rect, 0.0, colour);
            }
        }
    }
}

/// Shows the preview in `ui`, filling `size`, with orbit (drag), zoom (scroll) and pan
/// (right drag) on the mesh, or zoom and pan on the flat view.
pub fn show(
    ui: &mut Ui,
    state: &mut PreviewState,
    previews: &mut Previews,
    material: Option<MaterialFrame>,
    size: egui::Vec2,
) -> egui::Response {
    state.switch_camera();
    let (rect, response) = ui.allocate_exact_size(size, Sense::click_and_drag());
    steer(ui, state, &response);
    let request = material.map(|material| request(ui, state, material, rect));
    draw(
        ui,
        previews,
        Slot::Main,
        request,
        rect,
        state.view.background,
    );
    response
}

/// Shows a flat picture in `slot` (a node's thumbnail, or the tile beside the mesh): the
/// flat view of `state`'s placement, not interactive. Without a `material` it shows
/// what it last drew.
pub fn thumbnail(
    ui: &mut Ui,
    state: &PreviewState,
    previews: &mut Previews,
    (slot, material): (Slot, Option<MaterialFrame>),
    size: egui::Vec2,
) -> egui::Response {
    let mut flat = PreviewState::for_graph(&Preview::default());
    flat.flat = true;
    flat.view = state.view.clone();
    flat.view.distance = 3.6;
    flat.view.target = [0.0; 3];
    let (rect, response) = ui.allocate_exact_size(size, Sense::hover());
    let request = material.map(|material| request(ui, &flat, material, rect));
    draw(ui, previews, slot, request, rect, flat.view.background);
    response
}

/// Orbits, pans and zooms `state`'s camera as the pointer on `response` asks.
fn steer(ui: &Ui, state: &mut PreviewState, response: &egui::Response) {
    let rect = response.rect;
    let view = &mut state.view;
    if response.dragged_by(egui::PointerButton::Primary) && !state.flat {
        let delta = response.drag_delta();
        view.yaw -= delta.x * 0.4;
        view.pitch = (view.pitch + delta.y * 0.4).clamp(-89.0, 89.0);
    }
    if response.dragged_by(egui::PointerButton::Secondary)
        || (state.flat && response.dragged_by(egui::PointerButton::Primary))
    {
        let delta = response.drag_delta() / rect.height().max(1.0) * view.distance;
        let yaw = view.yaw.to_radians();
        let (right, up) = if state.flat {
            ([1.0, 0.0, 0.0], [0.0, 0.0, -1.0])
        } else {
            ([yaw.cos(), 0.0, -yaw.sin()], [0.0, 1.0, 0.0])
        };
        for k in 0..3 {
            view.target[k] -= right[k] * delta.x - up[k] * delta.y;
        }
    }
    if response.hovered() {
        let scroll = ui.input(|input| input.smooth_scroll_delta.y);
        view.distance = (view.distance * (-scroll * 0.002).exp()).clamp(0.3, 50.0);
    }
}

/// What a draft `width` pixels wide shown `pixels` wide says of itself: the fraction of
/// the resolution it was drawn at and its drawing time.
fn draft_note(pixels: f32, width: usize, took: std::time::Duration) -> String {
    let divisor = (pixels / width.max(1) as f32).round().max(1.0);
    let fraction = if divisor <= 1.0 {
        "full".to_string()
    } else {
        format!("1/{divisor:.0}")
    };
    format!(
        "draft: {fraction} resolution, {:.0} ms",
        took.as_secs_f64() * 1e3
    )
}

/// What to draw of `state` with `material` into `rect`: a draft while any pointer
/// button is held (a slider, an orbit, a node being moved), else the full picture (a
/// drag that changes nothing drawn posts nothing: [`Request::shown_by`]).
fn request(ui: &Ui, state: &PreviewState, material: MaterialFrame, rect: egui::Rect) -> Request {
    let pixels = (rect.size() * ui.ctx().pixels_per_point()).round();
    let dragging = ui.input(|input| input.pointer.any_down());
    let mesh = state.mesh_choice(&material.code.uses.mesh_fields);
    Request {
        material: material.code,
        params: material.params,
        tessellation: material.tessellation,
        mesh,
        view: state.frame_view(),
        environment: state.environment.clone(),
        size: (pixels.x.max(1.0) as u32, pixels.y.max(1.0) as u32),
        quality: if dragging {
            Quality::Draft
        } else {
            Quality::Full
        },
    }
}

fn draw(
    ui: &Ui,
    previews: &mut Previews,
    slot: Slot,
    request: Option<Request>,
    rect: egui::Rect,
    background: [f32; 3],
) {
    if let Some(request) = request {
        previews.post(slot, request);
    }
    previews.paint(ui, slot, rect, background);
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn a_draft_says_its_resolution_and_time() {
        let took = Duration::from_micros(12_400);
        assert_eq!(draft_note(443.0, 111, took), "draft: 1/4 resolution, 12 ms");
        assert_eq!(draft_note(443.0, 222, took), "draft: 1/2 resolution, 12 ms");
        assert_eq!(
            draft_note(443.0, 443, took),
            "draft: full resolution, 12 ms"
        );
    }

    #[test]
    fn time_plays_by_the_wall_clock_whatever_the_frame_rate() {
        let mut state = PreviewState::for_graph(&Preview::default());
        let start = Instant::now();
        state.tick(start);
        assert_eq!(state.view.time, 0.0, "paused: time stands still");
        state.playing = true;
        // Eight frames a second for two seconds, then a stall of three seconds.
        for frame in 0..=16 {
            state.tick(start + Duration::from_millis(125 * frame));
        }
        assert!((state.view.time - 2.0).abs() < 1e-4, "{}", state.view.time);
        state.tick(start + Duration::from_secs(5));
        assert!(
            (state.view.time - 2.25).abs() < 1e-4,
            "a stall adds a quarter second"
        );
        state.follow(&Preview::default());
        assert_eq!(
            (state.view.time, state.playing),
            (0.0, false),
            "a new graph starts at 0"
        );
    }

    #[test]
    fn a_graph_opened_starts_with_the_default_lighting() {
        let mut state = PreviewState::for_graph(&Preview::default());
        let default = state.look();
        state.view.exposure = 2.7;
        state.view.key_light = 0.1;
        state.view.environment_turn = 90.0;
        state.view.tone_map = crate::render::ToneMap::Aces;
        state.environment = EnvironmentChoice(Some(Arc::new(crate::render::Environment::from_fn(
            "red",
            8,
            |_| glam::Vec3::X,
        ))));
        state.follow(&Preview::default());
        let look = state.look();
        assert_eq!(
            (
                look.exposure,
                look.key_light,
                look.environment_turn,
                look.tone_map
            ),
            (
                default.exposure,
                default.key_light,
                default.environment_turn,
                default.tone_map
            ),
        );
        assert!(state.environment.0.is_none(), "lit by the sky again");
    }

    #[test]
    fn each_mesh_and_the_flat_view_keep_their_own_camera() {
        let mut state = PreviewState::for_graph(&Preview::default());
        state.switch_camera();
        state.view.distance = 1.0;
        state.view.yaw = 90.0;
        state.mesh = "cube".into();
        state.switch_camera();
        assert_eq!(
            Camera::of(&state.view),
            default_camera(),
            "the cube starts afresh"
        );
        state.view.distance = 7.0;
        state.flat = true;
        state.switch_camera();
        assert_eq!(
            Camera::of(&state.view),
            default_camera(),
            "so does the flat view"
        );
        state.flat = false;
        state.mesh = "sphere".into();
        state.switch_camera();
        assert_eq!(
            (state.view.distance, state.view.yaw),
            (1.0, 90.0),
            "the sphere's own"
        );
        state.reset_camera();
        assert_eq!(Camera::of(&state.view), default_camera());
        state.mesh = "cube".into();
        state.switch_camera();
        assert_eq!(state.view.distance, 7.0, "the cube's own");
    }
}
