//! Whether a flat domain's buffers repeat over it: a surface pass whose buffer wraps is
//! read across the tile's edges as if it went on, so a tile check of the material alone
//! (which evaluates the material past the edges) cannot see a pass that does not repeat
//! (a noise without a period, blurred). Each such pass is drawn again one domain width to
//! the right and one domain height further, only along its first column and row (into a
//! texture a texel wide and one a texel high), and compared with the same column and row
//! drawn over the domain itself.

use super::{PassDomain, PassRenderer, texture_format};
use crate::codegen::passes::PassKind;
use crate::nodes::passes::{BufferFormat, EdgeMode};
use crate::render::readback::Readback;
use crate::render::{FlatRect, GpuContext, RenderError};

/// How far a surface pass whose buffer wraps is from repeating over the domain: the
/// largest difference between its texels one domain width (height) on and its first
/// column (row), past one step of the buffer's format (rounding).
#[derive(Clone, Debug, PartialEq)]
pub struct WrapSeam {
    /// The pass's label (the node and output it renders).
    pub pass: String,
    pub left_right: f32,
    pub top_bottom: f32,
}

/// A buffer's first column and first row, as floats.
struct Strips {
    column: Vec<[f32; 4]>,
    row: Vec<[f32; 4]>,
}

impl PassRenderer {
    /// The seams of every surface pass whose buffer wraps, for the passes last rendered
    /// over `rect` at `time` (see [`PassRenderer::render`]); empty when none wraps.
    pub fn wrap_seams(
        &self,
        gpu: &GpuContext,
        rect: FlatRect,
        time: f32,
    ) -> Result<Vec<WrapSeam>, RenderError> {
        let rendered = self.rendered.lock().expect("pass buffers");
        let rendered = rendered.as_ref().expect("the passes rendered first");
        let (width, height) = (rect.x1 - rect.x0, rect.z1 - rect.z0);
        let moved = |dx: f64, dz: f64| FlatRect {
            x0: rect.x0 + dx,
            x1: rect.x1 + dx,
            z0: rect.z0 + dz,
            z1: rect.z1 + dz,
            y: rect.y,
        };
        let mut seams = Vec::new();
        for (index, pass) in self.passes.passes.iter().enumerate() {
            if !matches!(pass.kind, PassKind::Surface { .. }) || pass.spec.edge != EdgeMode::Wrap {
                continue;
            }
            let strips = |domain| self.strips(gpu, index, domain, time, &rendered.textures);
            let here = strips(rect)?;
            let right = strips(moved(width, 0.0))?;
            let below = strips(moved(0.0, height))?;
            let format = pass.spec.format;
            seams.push(WrapSeam {
                pass: pass.label.clone(),
                left_right: beyond_rounding(&right.column, &here.column, format),
                top_bottom: beyond_rounding(&below.row, &here.row, format),
            });
        }
        Ok(seams)
    }

    /// Surface pass `index` drawn over `rect` at `time`, only along its buffer's first
    /// column and first row (into textures one texel wide and one texel high, the view
    /// keeping the buffer's size), reading the buffers in `textures`.
    fn strips(
        &self,
        gpu: &GpuContext,
        index: usize,
        rect: FlatRect,
        time: f32,
        textures: &[wgpu::Texture],
    ) -> Result<Strips, RenderError> {
        let pass = &self.passes.passes[index];
        let buffer = &textures[self.storage[index]];
        let (width, height) = (buffer.width(), buffer.height());
        let format = texture_format(pass.spec.format);
        let strip = |extent| {
            crate::render::plain_texture(
                &gpu.device,
                &pass.label,
                extent,
                format,
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            )
        };
        let (column, row) = (strip((1, height)), strip((width, 1)));
        let pipeline = (self.pipelines[index].as_ref()).expect("a surface pass has a pipeline");
        let domain = (PassDomain::Flat(rect), time);
        // The view spans the whole buffer: the strips' texels are its first column and row.
        let groups = self.bind_groups(gpu, index, pipeline, domain, buffer, textures);
        let texel = pass.spec.format.texel_bytes() as u32;
        let readbacks = [
            Readback::new(gpu, (1, height), texel),
            Readback::new(gpu, (width, 1), texel),
        ];
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some(&pass.label),
            });
        for (target, readback) in [&column, &row].into_iter().zip(&readbacks) {
            {
                let view = target.create_view(&Default::default());
                let mut render = crate::render::tiles::clear_pass(
                    &mut encoder,
                    &view,
                    wgpu::Color::TRANSPARENT,
                    None,
                );
                render.set_pipeline(pipeline);
                for (index, group) in &groups {
                    render.set_bind_group(*index, group, &[]);
                }
                render.draw(0..3, 0..1);
            }
            readback.record_copy(&mut encoder, target, (target.width(), target.height()));
        }
        let submission = gpu.queue.submit([encoder.finish()]);
        let decode = |readback: &Readback, extent| {
            let mut texels = Vec::new();
            readback
                .read_rows(gpu, submission.clone(), extent, |_, bytes| {
                    let texels_of_row = bytes.chunks_exact(texel as usize);
                    texels.extend(texels_of_row.map(|bytes| decoded(bytes, pass.spec.format)))
                })
                .map(|()| texels)
        };
        Ok(Strips {
            column: decode(&readbacks[0], (1, height))?,
            row: decode(&readbacks[1], (width, 1))?,
        })
    }
}

/// One texel of a buffer of `format` as four floats.
fn decoded(bytes: &[u8], format: BufferFormat) -> [f32; 4] {
    match format {
        BufferFormat::Unorm8 => std::array::from_fn(|k| f32::from(bytes[k]) / 255.0),
        BufferFormat::Float16 => std::array::from_fn(|k| {
            half::f16::from_le_bytes([bytes[2 * k], bytes[2 * k + 1]]).to_f32()
        }),
        BufferFormat::Float32 => bytemuck::pod_read_unaligned(bytes),
    }
}

/// The largest difference between texels of `a` and `b`, each less one step of
/// `format` at its size (what rounding the same value may differ by).
fn beyond_rounding(a: &[[f32; 4]], b: &[[f32; 4]], format: BufferFormat) -> f32 {
    let step = |value: f32| match format {
        BufferFormat::Unorm8 => 1.0 / 255.0,
        BufferFormat::Float16 => value.abs() / 1024.0,
        BufferFormat::Float32 => 0.0,
    };
    (a.iter().zip(b))
        .flat_map(|(a, b)| a.iter().zip(b))
        .map(|(&a, &b)| ((a - b).abs() - step(a.max(b))).max(0.0))
        .fold(0.0, f32::max)
}
