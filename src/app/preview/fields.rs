//! GeoTextures and mesh fields in the editor: the preview mesh's distance fields and the
//! mesh fields the material reads computed in the background (with a progress bar),
//! distance fields' sources picked by clicking the mesh, and a field view (a colour
//! scale with isolines) in place of the material.

use crate::geodesic::{HeatOptions, Method};
use crate::graph::{FieldSource, Graph, NodeKind, RampInterpolation, RampStop, Value};
use crate::mesh::Mesh;
use crate::mesh_fields::{MeshField, MeshLanes};
use crate::messages::counted;
use crate::nodes::{ColorRamp, Field, MapRange, MapRangeMode, Mix};
use egui::Ui;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, mpsc};

/// The fields of the preview mesh and how the editor shows and edits them.
#[derive(Default)]
pub struct FieldState {
    /// The preview mesh carrying the fields in use, once solved, with what it was solved
    /// for.
    pub ready: Option<(String, Arc<Mesh>)>,
    job: Option<Job>,
    /// What the newest solve was started for (not restarted while unchanged, even when
    /// it failed).
    attempted: Option<String>,
    /// Why the newest solve failed.
    pub error: Option<String>,
    /// What the newest solve had to do differently (the robust heat method in place of
    /// the plain one, no refinement on a large mesh).
    pub notes: Vec<String>,
    /// The field whose sources clicks on the preview add or remove.
    pub picking: Option<usize>,
    /// Show this field as a colour scale with isolines instead of the material.
    pub view: Option<FieldView>,
}

/// A field the preview can show in place of the material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FieldView {
    /// Distance field `slot` of the graph's preview.
    Distance(usize),
    /// A mesh field the material reads.
    Mesh(MeshField),
}

/// A solve running on another thread.
struct Job {
    key: String,
    done: Arc<AtomicUsize>,
    total: Arc<AtomicUsize>,
    result: mpsc::Receiver<Result<(Mesh, Vec<String>), String>>,
}

impl FieldState {
    /// Starts a solve when the mesh, the sources, the distance fields in use or the mesh
    /// fields the material reads changed, and picks up a finished one. `base` gives the
    /// preview mesh (only called when a solve starts). Mesh fields come from
    /// [`crate::mesh_fields`]'s cache when this mesh had them computed before.
    pub fn update(
        &mut self,
        mesh_name: &str,
        base: impl FnOnce() -> Option<Arc<Mesh>>,
        fields: &[FieldSource],
        (used, mesh_lanes): ([bool; 4], MeshLanes),
    ) {
        if let Some(job) = &self.job
            && let Ok(result) = job.result.try_recv()
        {
            let key = job.key.clone();
            self.job = None;
            match result {
                Ok((mesh, notes)) => {
                    self.ready = Some((key, Arc::new(mesh)));
                    self.error = None;
                    self.notes = notes;
                }
                Err(error) => self.error = Some(error),
            }
        }
        if !used.iter().any(|&u| u) && mesh_lanes.iter().all(Option::is_none) {
            *self = FieldState {
                picking: self.picking,
                view: self.view,
                ..FieldState::default()
            };
            return;
        }
        let key = format!("{mesh_name}|{fields:?}|{used:?}|{mesh_lanes:?}");
        if self.attempted.as_ref() == Some(&key) {
            return;
        }
        self.attempted = Some(key.clone());
        let Some(mut mesh) = base().map(Arc::unwrap_or_clone) else {
            return;
        };
        let (done, total) = (Arc::new(AtomicUsize::new(0)), Arc::new(AtomicUsize::new(1)));
        let (sender, result) = mpsc::channel();
        let (fields, progress) = (fields.to_vec(), (done.clone(), total.clone()));
        std::thread::spawn(move || {
            let report = |d: usize, t: usize| {
                progress.0.store(d, Ordering::Relaxed);
                progress.1.store(t.max(1), Ordering::Relaxed);
            };
            let solved = crate::geodesic::attach_fields(&mut mesh, &fields, used, report)
                .map_err(|error| error.to_string())
                .and_then(|notes| {
                    crate::mesh_fields::attach_mesh_fields(&mut mesh, &mesh_lanes, report)
                        .map(|()| notes)
                        .map_err(|error| error.to_string())
                });
            let _ = sender.send(solved.map(|notes| (mesh, notes)));
        });
        self.error = None;
        self.job = Some(Job {
            key,
            done,
            total,
            result,
        });
    }

    /// The share of the running solve done, if one is running.
    pub fn progress(&self) -> Option<f32> {
        self.job.as_ref().map(|job| {
            job.done.load(Ordering::Relaxed) as f32 / job.total.load(Ordering::Relaxed) as f32
        })
    }
}

/// The range a mesh field's colour scale spans: its own, or for the unbounded
/// curvatures ±5 (a preview mesh is fitted to the unit sphere, whose curvature is 1).
fn shown_range(field: &MeshField) -> (f64, f64) {
    field.kind.range().unwrap_or((-5.0, 5.0))
}

/// A material showing `view` as a colour scale (red near a distance field's sources or
/// at a mesh field's low end, blue far or high) with isolines every 0.05 of the scale
/// (seed 003, figure 5.2).
pub fn field_view_graph(view: FieldView) -> Graph {
    let mut graph = Graph::default();
    let field = match view {
        FieldView::Distance(slot) => graph.add(
            "field",
            NodeKind::Field(Field {
                slot: slot.min(3) as u32,
            }),
        ),
        FieldView::Mesh(mesh_field) => {
            let read = graph.add("mesh field", NodeKind::MeshField(mesh_field));
            let (low, high) = shown_range(&mesh_field);
            let scale = graph.add(
                "to the scale",
                NodeKind::MapRange(MapRange {
                    mode: MapRangeMode::Linear,
                    clamp: true,
                }),
            );
            graph.set_input(scale, "from_min", Value::Float(low));
            graph.set_input(scale, "from_max", Value::Float(high));
            graph.connect(read, "value", scale, "x");
            scale
        }
    };
    let output = match view {
        FieldView::Distance(_) => "distance",
        FieldView::Mesh(_) => "result",
    };
    let stops = [
        (0.0, (0.85, 0.1, 0.1)),
        (0.25, (0.95, 0.75, 0.1)),
        (0.5, (0.2, 0.75, 0.25)),
        (0.75, (0.1, 0.55, 0.85)),
        (1.0, (0.15, 0.1, 0.6)),
    ];
    let scale = graph.add(
        "colour scale",
        NodeKind::ColorRamp(ColorRamp {
            stops: stops
                .iter()
                .map(|&(position, color)| RampStop { position, color })
                .collect(),
            interpolation: RampInterpolation::Linear,
        }),
    );
    let lines = graph.add("lines", NodeKind::Isolines);
    graph.set_input(lines, "spacing", Value::Float(0.05));
    graph.set_input(lines, "width", Value::Float(0.006));
    let inked = graph.add(
        "inked",
        NodeKind::Mix(Mix {
            ty: crate::graph::ValueType::Color,
        }),
    );
    graph.set_input(inked, "b", Value::Color(0.02, 0.02, 0.02));
    let material = graph.add("material", NodeKind::Material);
    graph.connect(field, output, scale, "factor");
    graph.connect(field, output, lines, "value");
    graph.connect(scale, "color", inked, "a");
    graph.connect(lines, "line", inked, "factor");
    graph.connect(inked, "result", material, "albedo");
    graph
}

/// The toggle showing `view` in place of the material.
fn view_toggle(ui: &mut Ui, state: &mut FieldState, view: FieldView) {
    let mut viewing = state.view == Some(view);
    if ui
        .toggle_value(&mut viewing, "view")
        .on_hover_text("show the field as colours and isolines")
        .changed()
    {
        state.view = viewing.then_some(view);
    }
}

/// Adds `vertex` to the sources of `field`, or removes it when it is one already.
pub fn toggle_source(field: &mut FieldSource, vertex: u32) {
    match field.sources.iter().position(|&s| s == vertex) {
        Some(index) => {
            field.sources.remove(index);
        }
        None => field.sources.push(vertex),
    }
}

const METHODS: [(&str, Method); 5] = [
    (
        "heat",
        Method::Heat(HeatOptions {
            time_factor: 1.0,
            robust: false,
            refine: true,
        }),
    ),
    (
        "heat, robust",
        Method::Heat(HeatOptions {
            time_factor: 1.0,
            robust: true,
            refine: true,
        }),
    ),
    (
        "heat, unrefined",
        Method::Heat(HeatOptions {
            time_factor: 1.0,
            robust: false,
            refine: false,
        }),
    ),
    ("exact", Method::Exact),
    ("dijkstra", Method::Dijkstra),
];

/// The fields section under the preview: per distance field its sources, method,
/// picking and view toggles, adding and removing them; then the mesh fields the material
/// reads (`mesh_lanes`), each with a view toggle.
pub fn fields_panel(
    ui: &mut Ui,
    fields: &mut Vec<FieldSource>,
    state: &mut FieldState,
    mesh_lanes: &MeshLanes,
) {
    ui.horizontal(|ui| {
        ui.label("Distance fields");
        if fields.len() < 4 && ui.small_button("+ field").clicked() {
            fields.push(FieldSource {
                sources: Vec::new(),
                method: METHODS[0].1,
            });
            state.picking = Some(fields.len() - 1);
        }
        if let Some(done) = state.progress() {
            ui.add(
                egui::ProgressBar::new(done)
                    .desired_width(120.0)
                    .text("solving"),
            );
            ui.ctx().request_repaint();
        }
    });
    let mut remove = None;
    for (slot, field) in fields.iter_mut().enumerate() {
        ui.horizontal(|ui| {
            ui.label(format!(
                "{slot}: {}",
                counted(field.sources.len(), "source")
            ));
            let name = METHODS
                .iter()
                .find(|(_, m)| *m == field.method)
                .map_or("heat", |(name, _)| name);
            egui::ComboBox::from_id_salt(("field method", slot))
                .selected_text(name)
                .show_ui(ui, |ui| {
                    for (label, method) in METHODS {
                        ui.selectable_value(&mut field.method, method, label);
                    }
                });
            let mut picking = state.picking == Some(slot);
            if ui
                .toggle_value(&mut picking, "pick")
                .on_hover_text("click the mesh to add or remove sources")
                .changed()
            {
                state.picking = picking.then_some(slot);
            }
            view_toggle(ui, state, FieldView::Distance(slot));
            if ui.small_button("clear").clicked() {
                field.sources.clear();
            }
            if ui
                .small_button("remove")
                .on_hover_text("remove this field")
                .clicked()
            {
                remove = Some(slot);
            }
        });
    }
    if let Some(slot) = remove {
        fields.remove(slot);
        state.picking = None;
        state.view = None;
    }
    let read: Vec<MeshField> = mesh_lanes.iter().flatten().copied().collect();
    if !read.is_empty() {
        ui.label("Mesh fields the material reads");
        for field in read {
            ui.horizontal(|ui| {
                ui.label(field.to_string());
                view_toggle(ui, state, FieldView::Mesh(field));
            });
        }
    }
    if let Some(FieldView::Mesh(field)) = state.view
        && !mesh_lanes.contains(&Some(field))
    {
        state.view = None;
    }
    if let Some(error) = &state.error {
        ui.colored_label(egui::Color32::LIGHT_RED, error);
    }
    for note in &state.notes {
        ui.colored_label(egui::Color32::YELLOW, note);
    }
    if state.picking.is_some() {
        ui.weak("Click the mesh to add a source; click it again to remove it.");
    }
}
