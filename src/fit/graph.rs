//! A graph fitted to a photo, end to end: the photo read into the albedo's encoding, the
//! graph checked and prepared, the fit run over the preview square, and the graph given
//! the fitted values, which it also records as a parameter preset named `fit`.

use super::optimise::{FitSettings, Fitted, Progress, fit};
use super::space::{Space, SpaceError};
use crate::eval::Evaluator;
use crate::graph::group::{BOUNDARY, GroupDef};
use crate::graph::parameters::{Given, ParameterError, set};
use crate::graph::{Graph, NodeId, NodeKind, PinRef};
use rustc_hash::{FxHashMap, FxHashSet};

/// The preset a fit records its values as.
pub const FIT_PRESET: &str = "fit";

/// Why a graph cannot be fitted.
#[derive(Debug)]
pub enum FitError {
    /// The graph does not check.
    Check(Vec<crate::graph::CheckError>),
    /// A node samples its input around the point (a buffered pass), which the fit does
    /// not differentiate through yet.
    Pass(String),
    /// The albedo reads a field of the mesh (a distance field, curvature, occlusion…),
    /// which the flat square a fit compares over does not have.
    SurfaceField(String),
    /// The parameters asked for cannot be fitted.
    Space(SpaceError),
    /// A fitted value does not go back into the graph.
    Parameter(ParameterError),
}

impl std::fmt::Display for FitError {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            FitError::Check(errors) => {
                let lines: Vec<String> = errors.iter().map(ToString::to_string).collect();
                f.write_str(&lines.join("\n"))
            }
            FitError::Pass(node) => write!(
                f,
                "node '{node}' is a buffered pass (it samples its input around the point): fitting does not differentiate through passes yet"
            ),
            FitError::SurfaceField(node) => write!(
                f,
                "node '{node}' reads a field of the mesh (distance, curvature, occlusion…) that the albedo depends on: a fit compares the albedo over a flat square, where mesh fields are constant"
            ),
            FitError::Space(error) => error.fmt(f),
            FitError::Parameter(error) => error.fmt(f),
        }
    }
}

/// The smallest side of a photo a fit compares with (the loss's pyramid and patches need
/// some room).
pub const SMALLEST_PHOTO_SIDE: u32 = 32;
/// The most pixels a photo may have (it is read whole before its middle is resampled).
pub const LARGEST_PHOTO_PIXELS: u64 = 64 * 1024 * 1024;

/// Reads the photo at `path`, refusing one that does not decode, one smaller than
/// [`SMALLEST_PHOTO_SIDE`] on a side and one larger than [`LARGEST_PHOTO_PIXELS`] (told
/// from its header, before it is decoded).
pub fn read_photo(path: &std::path::Path) -> Result<image::DynamicImage, String> {
    let open = || {
        (image::ImageReader::open(path))
            .and_then(|reader| reader.with_guessed_format())
            .map_err(|error| format!("cannot read the photo: {error}"))
    };
    let (width, height) =
        (open()?.into_dimensions()).map_err(|error| format!("cannot read the photo: {error}"))?;
    if width.min(height) < SMALLEST_PHOTO_SIDE {
        return Err(format!(
            "the photo is {width}×{height} pixels: give one at least {SMALLEST_PHOTO_SIDE} pixels on each side"
        ));
    }
    if u64::from(width) * u64::from(height) > LARGEST_PHOTO_PIXELS {
        return Err(format!(
            "the photo is {width}×{height} pixels: give one of at most {} megapixels (a fit compares at most 2048² pixels of it)",
            LARGEST_PHOTO_PIXELS / (1024 * 1024)
        ));
    }
    (open()?.decode()).map_err(|error| format!("cannot decode the photo: {error}"))
}

/// The photo's pixels in the encoding the graph's albedo has: display values (an 8-bit
/// file's own) for Blinn-Phong materials, linear values for metallic-roughness ones (an
/// 8-bit file decoded from sRGB; a float file, OpenEXR or Radiance, is linear already and
/// is encoded for display where the albedo is).
pub fn photo_pixels(photo: &image::DynamicImage, linear_albedo: bool) -> image::Rgb32FImage {
    use crate::bitmaps::{linear_to_srgb, srgb_to_linear};
    let float_file = matches!(
        photo,
        image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_)
    );
    let mut pixels = photo.to_rgb32f();
    for pixel in pixels.pixels_mut() {
        for lane in &mut pixel.0 {
            *lane = match (float_file, linear_albedo) {
                (false, true) => srgb_to_linear(*lane),
                (true, false) => linear_to_srgb(lane.clamp(0.0, 1.0)),
                _ => *lane,
            };
        }
    }
    pixels
}

/// What a graph's albedo reads: the nodes every input of which can change it, the
/// inputs of group nodes that can (only those the outputs it reads depend on), and the
/// material nodes.
struct AlbedoReach {
    whole: FxHashSet<NodeId>,
    group_inputs: FxHashSet<(NodeId, String)>,
    materials: Vec<NodeId>,
}

/// The inputs of group `definition` that output `output` depends on (nodes inside it,
/// nested groups included, taken whole).
fn group_inputs_reaching(definition: &GroupDef, output: &str) -> Vec<String> {
    let into = |node: NodeId| (definition.wires.iter()).filter(move |w| w.to.node == node);
    let mut inside = FxHashSet::default();
    let mut stack: Vec<NodeId> = (into(BOUNDARY))
        .filter(|wire| wire.to.pin == output)
        .map(|wire| wire.from.node)
        .collect();
    while let Some(node) = stack.pop() {
        if node != BOUNDARY && inside.insert(node) {
            stack.extend(into(node).map(|wire| wire.from.node));
        }
    }
    (definition.wires.iter())
        .filter(|wire| wire.from.node == BOUNDARY)
        .filter(|wire| {
            inside.contains(&wire.to.node) || (wire.to.node == BOUNDARY && wire.to.pin == output)
        })
        .map(|wire| wire.from.pin.clone())
        .collect()
}

impl AlbedoReach {
    /// Walks back from the materials' albedo pins, output by output.
    fn of(graph: &Graph) -> AlbedoReach {
        let materials: Vec<_> = (graph.nodes.iter())
            .filter(|node| matches!(node.kind, NodeKind::Material))
            .map(|node| node.id)
            .collect();
        let definitions: FxHashMap<NodeId, &GroupDef> = (graph.nodes.iter())
            .filter_map(|node| match &node.kind {
                NodeKind::Group(group) => Some((node.id, graph.groups.get(&group.name)?)),
                _ => None,
            })
            .collect();
        // The outputs wired into `pin` of `node` (every pin of it for `None`).
        let sources = |node: NodeId, pin: Option<&str>| -> Vec<(NodeId, String)> {
            (graph.wires.iter())
                .filter(|w| w.to.node == node && pin.is_none_or(|pin| w.to.pin == pin))
                .map(|w| (w.from.node, w.from.pin.clone()))
                .collect()
        };
        let mut queue: Vec<(NodeId, String)> = (materials.iter())
            .flat_map(|&material| sources(material, Some("albedo")))
            .collect();
        let (mut whole, mut group_inputs) = (FxHashSet::default(), FxHashSet::default());
        let mut seen = FxHashSet::default();
        while let Some((node, output)) = queue.pop() {
            if !seen.insert((node, output.clone())) {
                continue;
            }
            match definitions.get(&node) {
                Some(definition) => {
                    for input in group_inputs_reaching(definition, &output) {
                        queue.extend(sources(node, Some(&input)));
                        group_inputs.insert((node, input));
                    }
                }
                None => {
                    whole.insert(node);
                    queue.extend(sources(node, None));
                }
            }
        }
        AlbedoReach {
            whole,
            group_inputs,
            materials,
        }
    }

    /// Whether node `node` is read by the albedo (whole, or some of its inputs).
    fn reads(&self, node: NodeId) -> bool {
        self.whole.contains(&node) || self.group_inputs.iter().any(|(n, _)| *n == node)
    }

    /// Whether `pin` can change the albedo: the material's albedo pin, an input of a
    /// node the albedo reads, or a group's input its read outputs depend on.
    fn reaches(&self, pin: &PinRef) -> bool {
        self.whole.contains(&pin.node)
            || self.group_inputs.contains(&(pin.node, pin.pin.clone()))
            || (self.materials.contains(&pin.node) && pin.pin == "albedo")
    }
}

/// What fitting a graph gave: the graph with the fitted values (and the `fit` preset),
/// the fit's record, and the space it moved in.
pub struct FittedGraph {
    pub graph: Graph,
    pub fitted: Fitted,
    pub space: Space,
}

/// A graph ready to fit: its evaluator, the space of its fitted parameters and the
/// square its albedo is compared over (the preview's).
pub struct Prepared {
    pub evaluator: Evaluator,
    pub space: Space,
    pub rect: crate::render::FlatRect,
}

/// Prepares `graph` to fit its exposed parameters that reach the albedo (all continuous
/// ones, or those `only` names), refusing a graph that does not check or holds a
/// buffered pass.
pub fn prepare(graph: &Graph, only: Option<&[String]>) -> Result<Prepared, FitError> {
    let evaluator = Evaluator::new(graph).map_err(FitError::Check)?;
    let checked = evaluator.graph();
    if let Some(pass) =
        (checked.order.iter()).find(|node| node.signature.inputs.iter().any(|pin| pin.sampled))
    {
        return Err(FitError::Pass(pass.node.display_name().to_string()));
    }
    let reach = AlbedoReach::of(graph);
    let surface_field = (checked.order.iter()).find(|checked| {
        let kind = std::slice::from_ref(&checked.node.kind);
        // A node inlined from a group counts as its top-level group node.
        let top = checked
            .node
            .origin
            .as_ref()
            .map_or(checked.node.id, |o| o.top);
        reach.reads(top)
            && (matches!(checked.node.kind, NodeKind::Field(_))
                || !crate::nodes::mesh_field::fields_read(kind).is_empty())
    });
    if let Some(field) = surface_field {
        return Err(FitError::SurfaceField(
            field.node.display_name().to_string(),
        ));
    }
    let space = Space::of(&checked.parameters, |p| reach.reaches(&p.target), only)
        .map_err(FitError::Space)?;
    Ok(Prepared {
        space,
        rect: crate::render::preview_rect(&graph.preview),
        evaluator,
    })
}

/// Fits the exposed parameters of `graph` (all continuous ones that reach the albedo,
/// or those `only` names) so that its albedo over the preview square looks like
/// `photo`.
pub fn fit_graph(
    graph: &Graph,
    photo: &image::DynamicImage,
    only: Option<&[String]>,
    settings: &FitSettings,
    progress: impl FnMut(&Progress) -> bool,
) -> Result<FittedGraph, FitError> {
    let Prepared {
        evaluator,
        space,
        rect,
    } = prepare(graph, only)?;
    let checked = evaluator.graph();
    let pixels = photo_pixels(photo, checked.shading.is_linear());
    let fitted = fit(&evaluator, rect, &space, &pixels, settings, progress);
    let space = space.with_choices(&fitted.choices);
    let mut graph = graph.clone();
    for (_, name, lanes) in space.fitted_values(&fitted.places) {
        let given = match lanes[..] {
            [number] => Given::Number(number),
            _ => Given::List(lanes),
        };
        set(&mut graph, name, &given).map_err(FitError::Parameter)?;
    }
    // Every exposed value, the fitted ones and those it started from (a preset or
    // `--set` applied before), so that the preset gives the fitted look on its own.
    let preset = (crate::graph::parameters::exposed(&graph).into_iter())
        .map(|parameter| (parameter.name, parameter.value))
        .collect();
    graph.presets.insert(FIT_PRESET.to_string(), preset);
    Ok(FittedGraph {
        graph,
        fitted,
        space,
    })
}
