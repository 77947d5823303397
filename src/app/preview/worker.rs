//! The thread that draws the editor's previews (the material on its mesh, and the
//! selected node's output) on a wgpu device of its own. The UI thread only posts what
//! to draw and shows the newest image that came back, so a driver compiling a new
//! pipeline, or a slow frame, never holds up a click: the last good image stays on
//! screen meanwhile. Each preview keeps one request waiting at most — a newer one
//! replaces it — so the thread always draws the latest state.

use crate::app::preview::drawing_thread::DrawingThread;
use crate::graph::CheckedGraph;
use crate::mesh::{Mesh, Refinement};
use crate::render::{
    Environment, EnvironmentMaps, GpuContext, LiveMaterialCode, LiveRenderer, MeshView, Quality,
};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Condvar, Mutex};

/// Which preview a request is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    /// The material on the preview mesh.
    Main = 0,
    /// The selected node's output, flat.
    Node = 1,
    /// A texture graph's material over the unit tile, flat, beside the mesh.
    Tile = 2,
}

impl Slot {
    /// Every slot, in the order waiting requests are drawn.
    pub const ALL: [Slot; 3] = [Slot::Main, Slot::Node, Slot::Tile];
}

/// The mesh a preview draws.
#[derive(Clone)]
pub struct MeshChoice {
    /// What identifies it: a primitive's name, a file's path, or the solved mesh's key.
    pub key: String,
    /// The mesh itself, or `None` for the primitive `key` names (the sphere when `key`
    /// names none), made on the drawing thread.
    pub mesh: Option<Arc<Mesh>>,
}

impl PartialEq for MeshChoice {
    fn eq(&self, other: &MeshChoice) -> bool {
        self.key == other.key
            && match (&self.mesh, &other.mesh) {
                (Some(a), Some(b)) => Arc::ptr_eq(a, b),
                (None, None) => true,
                _ => false,
            }
    }
}

/// The material's graph as it is now (its constants baked) and the refinement asked
/// for, for adaptive tessellation of a displaced mesh on the drawing thread.
#[derive(Clone)]
pub struct TessellationInput {
    /// The graph revision `graph` was checked at.
    pub revision: u64,
    pub graph: Arc<CheckedGraph>,
    pub refinement: Refinement,
}

impl PartialEq for TessellationInput {
    fn eq(&self, other: &TessellationInput) -> bool {
        // The graph changes with the revision: no need to compare it.
        self.revision == other.revision && self.refinement == other.refinement
    }
}

/// The environment lighting metallic-roughness materials: `None` for the procedural
/// sky. Two choices are the same when they hold the same loaded environment.
#[derive(Clone, Default)]
pub struct EnvironmentChoice(pub Option<Arc<Environment>>);

impl PartialEq for EnvironmentChoice {
    fn eq(&self, other: &EnvironmentChoice) -> bool {
        match (&self.0, &other.0) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (None, None) => true,
            _ => false,
        }
    }
}

/// One frame to draw.
#[derive(Clone, PartialEq)]
pub struct Request {
    pub material: LiveMaterialCode,
    pub params: Arc<[[f32; 4]]>,
    /// Set when the mesh is refined for the view (full-quality frames only; drafts
    /// reuse the last refined mesh of the same material and mesh).
    pub tessellation: Option<TessellationInput>,
    pub mesh: MeshChoice,
    pub view: MeshView,
    pub environment: EnvironmentChoice,
    /// The preview's size in pixels (drafts draw at half of it).
    pub size: (u32, u32),
    pub quality: Quality,
}

impl Request {
    /// Whether `posted` already shows what this asks for, as finely or finer: the same
    /// request, or this one a draft of that full picture (a drag that changes nothing
    /// drawn, such as a box selection, keeps the full picture rather than a draft).
    pub fn shown_by(&self, posted: &Request) -> bool {
        self == posted
            || (self.quality == Quality::Draft
                && posted.quality == Quality::Full
                && Request {
                    quality: Quality::Full,
                    ..self.clone()
                } == *posted)
    }
}

/// A frame drawn, or why it could not be.
pub struct Drawn {
    pub slot: Slot,
    /// The number the request was posted under.
    pub id: u64,
    /// How finely it was drawn.
    pub quality: Quality,
    /// How long drawing it took, readback included.
    pub took: std::time::Duration,
    pub image: Result<egui::ColorImage, String>,
    /// Materials built so far for this slot.
    pub materials_built: u64,
}

/// Requests waiting, one per slot, and whether the UI has gone.
#[derive(Default)]
struct Mailbox {
    waiting: [Option<(u64, Request)>; Slot::ALL.len()],
    closed: bool,
}

/// The UI thread's end: posts requests, receives frames; dropping it ends the thread
/// (and waits for it, see [`DrawingThread`]).
pub struct Worker {
    mailbox: Arc<(Mutex<Mailbox>, Condvar)>,
    drawn: Receiver<Drawn>,
    thread: DrawingThread,
}

impl Worker {
    /// Starts the thread; `wake` is called after each frame (the UI repaints then).
    pub fn start(wake: impl Fn() + Send + 'static) -> Worker {
        let mailbox = Arc::new((Mutex::new(Mailbox::default()), Condvar::new()));
        let (sender, drawn) = channel();
        let shared = Arc::clone(&mailbox);
        let thread = DrawingThread::spawn("veneer preview", move || run(&shared, &sender, wake));
        Worker {
            mailbox,
            drawn,
            thread,
        }
    }

    /// Posts `request` for `slot` under the number `id`, replacing one still waiting.
    pub fn post(&self, slot: Slot, id: u64, request: Request) {
        let (lock, wakeup) = &*self.mailbox;
        if let Ok(mut mailbox) = lock.lock() {
            mailbox.waiting[slot as usize] = Some((id, request));
            wakeup.notify_one();
        }
    }

    /// Frames drawn since the last call.
    pub fn drawn(&self) -> Vec<Drawn> {
        self.drawn.try_iter().collect()
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        let (lock, wakeup) = &*self.mailbox;
        if let Ok(mut mailbox) = lock.lock() {
            mailbox.closed = true;
            wakeup.notify_one();
        }
        self.thread.wait();
    }
}

/// What the thread does next.
enum Task {
    Draw(Slot, u64, Request),
    /// Nothing waits: build the draft pipeline of the material just drawn, so that the
    /// first drag after an edit does not wait for it.
    Prepare(Slot, LiveMaterialCode),
}

fn run(mailbox: &(Mutex<Mailbox>, Condvar), drawn: &Sender<Drawn>, wake: impl Fn()) {
    let gpu = GpuContext::new().map_err(|error| error.to_string());
    let mut renderers: [LiveRenderer; Slot::ALL.len()] = Default::default();
    let mut primitives: [Option<(String, Arc<Mesh>)>; Slot::ALL.len()] = Default::default();
    let mut refined = Refinements::default();
    let mut lit: Option<(EnvironmentChoice, Arc<EnvironmentMaps>)> = None;
    let mut idle: Option<(Slot, LiveMaterialCode)> = None;
    while let Some(task) = next_task(mailbox, &mut idle) {
        match task {
            Task::Draw(slot, id, mut request) => {
                let renderer = &mut renderers[slot as usize];
                let started = std::time::Instant::now();
                let image = gpu.as_ref().map_err(Clone::clone).and_then(|gpu| {
                    let mut mesh = resolve(&mut primitives[slot as usize], &request.mesh);
                    if let Some(input) = request.tessellation.clone() {
                        (request.mesh.key, mesh) = refined.mesh_for(&request, &input, mesh);
                    }
                    let maps = environment_maps(gpu, &mut lit, &request.environment)?;
                    draw(gpu, renderer, &request, &mesh, &maps)
                });
                if image.is_ok() && request.quality == Quality::Full {
                    idle = Some((slot, request.material.clone()));
                }
                let reply = Drawn {
                    slot,
                    id,
                    quality: request.quality,
                    took: started.elapsed(),
                    image,
                    materials_built: renderer.materials_built,
                };
                if drawn.send(reply).is_err() {
                    return;
                }
                wake();
            }
            Task::Prepare(slot, material) => {
                if let Ok(gpu) = &gpu {
                    // A failure shows when a draft is drawn.
                    let _ = renderers[slot as usize].prepare(gpu, &material, Quality::Draft);
                }
            }
        }
    }
}

/// Waits for a request (slot order) or, with none waiting, hands out the idle task;
/// `None` once the UI has gone.
fn next_task(
    mailbox: &(Mutex<Mailbox>, Condvar),
    idle: &mut Option<(Slot, LiveMaterialCode)>,
) -> Option<Task> {
    let (lock, wakeup) = mailbox;
    let mut waiting = lock.lock().ok()?;
    loop {
        if waiting.closed {
            return None;
        }
        for slot in Slot::ALL {
            if let Some((id, request)) = waiting.waiting[slot as usize].take() {
                return Some(Task::Draw(slot, id, request));
            }
        }
        if let Some((slot, material)) = idle.take() {
            return Some(Task::Prepare(slot, material));
        }
        waiting = wakeup.wait(waiting).ok()?;
    }
}

/// The newest mesh refined for a view, and what it was refined for.
#[derive(Default)]
struct Refinements {
    last: Option<RefinedMesh>,
    /// Counts refinements, so that each refined mesh uploads under a key of its own.
    made: u64,
}

struct RefinedMesh {
    /// The key of the mesh it refines.
    base: String,
    /// What it was refined for.
    input: TessellationInput,
    view: MeshView,
    size: (u32, u32),
    key: String,
    mesh: Arc<Mesh>,
}

impl Refinements {
    /// The mesh to draw for `request` and its key: `base` refined for the request's
    /// material, view and size when it is a full frame (the last refinement when none of
    /// them changed); for a draft, the last refinement of the same mesh, whatever it was
    /// refined for (closer to the surface than the mesh itself), or `base` if none.
    fn mesh_for(
        &mut self,
        request: &Request,
        input: &TessellationInput,
        base: Arc<Mesh>,
    ) -> (String, Arc<Mesh>) {
        if let Some(last) = &self.last
            && last.base == request.mesh.key
            && (request.quality == Quality::Draft
                || (last.input == *input && last.view == request.view && last.size == request.size))
        {
            return (last.key.clone(), Arc::clone(&last.mesh));
        }
        if request.quality == Quality::Draft {
            return (request.mesh.key.clone(), base);
        }
        let mesh = crate::render::tessellate(
            &input.graph,
            &base,
            &request.view,
            request.size.1,
            &input.refinement,
        )
        .mesh;
        self.made += 1;
        let refined = RefinedMesh {
            base: request.mesh.key.clone(),
            input: input.clone(),
            view: request.view.clone(),
            size: request.size,
            key: format!("{}#refined{}", request.mesh.key, self.made),
            mesh: Arc::new(mesh),
        };
        let drawn = (refined.key.clone(), Arc::clone(&refined.mesh));
        self.last = Some(refined);
        drawn
    }
}

/// The lighting maps of `choice`, derived only when the choice changes (the sky's are
/// the device's own, derived once).
fn environment_maps(
    gpu: &GpuContext,
    cache: &mut Option<(EnvironmentChoice, Arc<EnvironmentMaps>)>,
    choice: &EnvironmentChoice,
) -> Result<Arc<EnvironmentMaps>, String> {
    if let Some((seen, maps)) = cache.as_ref()
        && seen == choice
    {
        return Ok(Arc::clone(maps));
    }
    let maps = match &choice.0 {
        None => gpu.sky(),
        Some(environment) => EnvironmentMaps::new(gpu, environment).map(Arc::new),
    }
    .map_err(|error| error.to_string())?;
    *cache = Some((choice.clone(), Arc::clone(&maps)));
    Ok(maps)
}

/// The mesh `choice` names, making a primitive only when the name changes.
fn resolve(cache: &mut Option<(String, Arc<Mesh>)>, choice: &MeshChoice) -> Arc<Mesh> {
    if let Some(mesh) = &choice.mesh {
        return Arc::clone(mesh);
    }
    if let Some((key, mesh)) = cache.as_ref()
        && *key == choice.key
    {
        return Arc::clone(mesh);
    }
    let mesh = crate::mesh::primitive(&choice.key)
        .or_else(|| crate::mesh::primitive("sphere"))
        .expect("the sphere exists");
    let mesh = Arc::new(mesh);
    *cache = Some((choice.key.clone(), Arc::clone(&mesh)));
    mesh
}

fn draw(
    gpu: &GpuContext,
    renderer: &mut LiveRenderer,
    request: &Request,
    mesh: &Mesh,
    environment: &Arc<EnvironmentMaps>,
) -> Result<egui::ColorImage, String> {
    let (size, mut pixels) = renderer
        .render(
            gpu,
            &request.material,
            &request.params,
            &request.mesh.key,
            mesh,
            &request.view,
            environment,
            request.size,
            request.quality,
        )
        .map_err(|error| error.to_string())?;
    // The preview is opaque whatever alpha the material has (holes show the background).
    for pixel in pixels.chunks_exact_mut(4) {
        pixel[3] = 255;
    }
    Ok(egui::ColorImage::from_rgba_premultiplied(
        [size.0 as usize, size.1 as usize],
        &pixels,
    ))
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_dropped_worker_has_waited_for_its_thread_and_device() {
        super::super::drawing_thread::assert_dropping_waits_for_the_thread(super::Worker::start);
    }
}
