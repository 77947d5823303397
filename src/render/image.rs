//! Rendering a compiled material to an 8-bit image, as `veneer render`, snapshots and
//! the editor's PNG export do.

use super::mesh_view::Relief;
use super::tessellation::{Tessellated, tessellate};
use super::{
    FlatRect, FlatRenderer, GpuContext, MeshRenderer, MeshView, RenderError, albedo_to_rgb8,
};
use crate::codegen::{Compiled, ParamMode, SurfaceUse};
use crate::graph::Preview;
use serde::{Deserialize, Serialize};

/// How a graph is shown in an image.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum View {
    /// Lit, on a primitive mesh (`None`: the graph's preview mesh), as in the preview.
    Mesh(Option<String>),
    /// Albedo, unlit, over a rectangle of a plane (`veneer render --flat`).
    Flat(FlatRect),
    /// Albedo, unlit, over the square the graph's preview covers (centre ± size, y = centre + 0.5).
    PreviewFlat,
}

/// An 8-bit image, rows from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    /// 3 (RGB, flat renders) or 4 (RGBA, mesh renders).
    pub channels: usize,
    pub pixels: Vec<u8>,
}

impl Image {
    /// PNG bytes of the image.
    pub fn to_png(&self) -> Result<Vec<u8>, RenderError> {
        use image::ImageEncoder;
        let color = if self.channels == 3 {
            image::ExtendedColorType::Rgb8
        } else {
            image::ExtendedColorType::Rgba8
        };
        let mut bytes = Vec::new();
        image::codecs::png::PngEncoder::new(&mut bytes)
            .write_image(&self.pixels, self.width, self.height, color)
            .map_err(RenderError::Encode)?;
        Ok(bytes)
    }

    /// Decodes a PNG (RGB stays RGB; anything else becomes RGBA).
    pub fn from_png(bytes: &[u8]) -> Result<Image, String> {
        let decoded = image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
            .map_err(|e| e.to_string())?;
        let (width, height) = (decoded.width(), decoded.height());
        Ok(match decoded {
            image::DynamicImage::ImageRgb8(rgb) => Image {
                width,
                height,
                channels: 3,
                pixels: rgb.into_raw(),
            },
            other => Image {
                width,
                height,
                channels: 4,
                pixels: other.to_rgba8().into_raw(),
            },
        })
    }
}

/// The flat rectangle a graph's preview covers.
pub fn preview_rect(preview: &Preview) -> FlatRect {
    let (c, size) = (preview.center, preview.size);
    FlatRect {
        x0: c.0 - size,
        z0: c.2 - size,
        x1: c.0 + size,
        z1: c.2 + size,
        y: c.1 + 0.5,
    }
}

/// Where a graph's preview places its mesh in texture space: the centre and size of
/// the square it covers.
pub fn texture_placement(preview: &Preview) -> ([f32; 3], f32) {
    let center = preview.center;
    (
        [center.0 as f32, center.1 as f32, center.2 as f32],
        preview.size as f32,
    )
}

/// The preview mesh `name` carrying the distance fields of `preview` and the mesh
/// fields that the material uses (none are computed when it reads none); progress
/// counts the distance fields' vertices, then the mesh fields'.
pub fn mesh_with_fields(
    preview: &Preview,
    name: &str,
    uses: &SurfaceUse,
    mut progress: impl FnMut(usize, usize),
) -> Result<crate::mesh::Mesh, RenderError> {
    let mut mesh = crate::mesh::preview_mesh(name)?;
    // A field the robust heat method solved in place of the plain one is as good: the
    // render has no use for the notes saying so (the editor shows them).
    crate::geodesic::attach_fields(&mut mesh, &preview.fields, uses.fields, &mut progress)
        .map_err(|error| RenderError::Fields {
            mesh: name.to_string(),
            error,
        })?;
    crate::mesh_fields::attach_mesh_fields(&mut mesh, &uses.mesh_fields, progress).map_err(
        |error| RenderError::MeshFields {
            mesh: name.to_string(),
            error,
        },
    )?;
    Ok(mesh)
}

/// Refuses a material compiled with its parameters in a uniform block (the editor's):
/// the headless renderers bind no parameter buffer.
pub fn baked_parameters(compiled: &Compiled) -> Result<(), RenderError> {
    match compiled.options.params {
        ParamMode::Baked => Ok(()),
        ParamMode::Uniform | ParamMode::Storage | ParamMode::Named => Err(RenderError::Invalid(
            "the material was compiled with its parameters in a buffer; renders and bakes take baked parameters".into(),
        )),
    }
}

/// The passes of a material drawn over `mesh` (`None` for a single-pass material),
/// rendered for an output of `size` texels at `time`: their buffers span the mesh's UV
/// layout, its points placed in texture space at `placement` (centre and size), so
/// that the material reads them at the mesh's UVs. Files are uploaded as they are.
pub fn mesh_passes(
    gpu: &GpuContext,
    compiled: &Compiled,
    mesh: &super::GpuMesh,
    placement: ([f32; 3], f32),
    size: u32,
    time: f32,
) -> Result<Option<super::PassRenderer>, RenderError> {
    if compiled.passes.is_empty() {
        return Ok(None);
    }
    let passes = super::PassRenderer::new(gpu, &compiled.passes, None)?;
    passes.render(gpu, super::PassDomain::Mesh { mesh, placement }, size, time)?;
    Ok(Some(passes))
}

/// Renders a compiled material as `view` at size×size pixels and time `time`, with the
/// detail it was compiled with (snapshots and the CPU reference expect every octave).
pub fn render_material(
    gpu: &GpuContext,
    compiled: &Compiled,
    view: &View,
    size: u32,
    time: f32,
) -> Result<Image, RenderError> {
    Ok(render_material_with(gpu, compiled, view, size, time, MeshLook::default())?.image)
}

/// How a mesh render shows its material, beyond what the graph says.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshLook {
    /// How the height shows.
    pub relief: Relief,
    /// Metallic-roughness materials: the tone mapper and the exposure in stops.
    pub tone_map: super::ToneMap,
    pub exposure: f32,
    /// Metallic-roughness materials: the environment lighting them (`None`: the
    /// procedural sky), turned about +y by `environment_turn` degrees, the key light's
    /// irradiance, and what shows behind the mesh.
    pub environment: Option<std::sync::Arc<super::Environment>>,
    pub environment_turn: f32,
    pub key_light: f32,
    pub backdrop: super::Backdrop,
}

impl Default for MeshLook {
    fn default() -> MeshLook {
        MeshLook {
            relief: Relief::default(),
            tone_map: super::ToneMap::default(),
            exposure: 0.0,
            environment: None,
            environment_turn: 0.0,
            key_light: super::DEFAULT_KEY_LIGHT,
            backdrop: super::Backdrop::default(),
        }
    }
}

/// A rendered image and how its mesh was tessellated.
pub struct Rendered {
    pub image: Image,
    /// What adaptive tessellation did (`None` when the mesh was drawn as it is).
    pub tessellated: Option<Tessellated>,
}

/// [`render_material`] with `look` (the height's relief, tone mapping); a displaced material
/// whose preview asks for tessellation has its mesh refined for this view first.
pub fn render_material_with(
    gpu: &GpuContext,
    compiled: &Compiled,
    view: &View,
    size: u32,
    time: f32,
    look: MeshLook,
) -> Result<Rendered, RenderError> {
    let relief = look.relief;
    baked_parameters(compiled)?;
    let module = &compiled.module;
    let flat = |rect: FlatRect| -> Result<Rendered, RenderError> {
        let pixels = FlatRenderer::for_compiled(gpu, compiled)?.render(gpu, rect, size, time)?;
        if let Some(why) = super::non_finite("albedo", &pixels, size as usize, 0) {
            return Err(RenderError::Invalid(why));
        }
        Ok(Rendered {
            image: Image {
                width: size,
                height: size,
                channels: 3,
                pixels: albedo_to_rgb8(&pixels),
            },
            tessellated: None,
        })
    };
    let preview = &compiled.preview;
    match view {
        View::Flat(rect) => flat(*rect),
        View::PreviewFlat => flat(preview_rect(preview)),
        View::Mesh(name) => {
            let name = name.as_deref().unwrap_or(&preview.mesh);
            let mut mesh = mesh_with_fields(preview, name, &module.uses, |_, _| {})?;
            // The CPU evaluator that refines the mesh reads files but renders no passes.
            let rendered_passes = !compiled.passes.uploads_only();
            if rendered_passes {
                // Buffers over the surface need a layout giving each point its own texels.
                mesh = mesh.with_own_texels(size);
            }
            let mut mesh_view = MeshView::for_preview(preview);
            mesh_view.time = time;
            mesh_view.tone_map = look.tone_map;
            mesh_view.exposure = look.exposure;
            mesh_view.environment_turn = look.environment_turn;
            mesh_view.key_light = look.key_light;
            mesh_view.backdrop = look.backdrop;
            let tessellated = match preview.tessellation {
                Some(settings)
                    if module.uses.displacement
                        && relief == Relief::Displaced
                        && !rendered_passes =>
                {
                    let before = mesh.triangle_count();
                    let refined = tessellate(
                        &compiled.checked,
                        &mesh,
                        &mesh_view,
                        size,
                        &settings.refinement(),
                    );
                    mesh = refined.mesh;
                    Some(Tessellated {
                        levels: refined.levels,
                        triangles: (before, mesh.triangle_count()),
                        limited: refined.limited,
                    })
                }
                _ => None,
            };
            let mut renderer = MeshRenderer::lit(
                gpu,
                &module.source,
                module.uses,
                relief,
                look.environment.as_deref(),
            )?;
            if !compiled.passes.is_empty() {
                let uploaded = super::GpuMesh::new(&gpu.device, &mesh);
                let placement = (mesh_view.center, mesh_view.size);
                if let Some(passes) = mesh_passes(gpu, compiled, &uploaded, placement, size, time)?
                {
                    renderer.bind_passes(gpu, &passes);
                }
            }
            let pixels = renderer.render(gpu, &mesh, &mesh_view, size)?;
            Ok(Rendered {
                image: Image {
                    width: size,
                    height: size,
                    channels: 4,
                    pixels: pixels.into_flattened(),
                },
                tessellated,
            })
        }
    }
}
