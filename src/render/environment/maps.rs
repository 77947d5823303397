//! The image-based lighting maps of one environment, derived on the GPU
//! (`shaders/environment_bake.wgsl`): what the metallic-roughness preview samples.

use super::Environment;
use crate::render::{GpuContext, RenderError, fullscreen_pipeline};
use half::f16;

/// The GPU's format of every map: filterable half floats, renderable everywhere.
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// The prefiltered specular chain: 256 × 128 for roughness 0 down to 8 × 4 for
/// roughness 1, the roughness of level k being k / (levels − 1).
const PREFILTERED_WIDTH: u32 = 256;
const PREFILTERED_LEVELS: u32 = 6;
/// The irradiance map's width (it is smooth: low frequencies only), and the most
/// panorama texels across that each of its texels sums.
const IRRADIANCE_WIDTH: u32 = 64;
const IRRADIANCE_SOURCE_WIDTH: u32 = 64;
/// The split-sum table's size (n·v × roughness).
const BRDF_SIZE: u32 = 128;
/// GGX samples a texel of the prefiltered chain and of the split-sum table.
const SAMPLES: u32 = 512;

/// An environment's lighting maps on the GPU, ready to bind.
pub struct EnvironmentMaps {
    /// The environment's name (`sky`, or its file's).
    pub name: String,
    /// The panorama itself with its box-filtered mip chain (the sharp background).
    pub source: wgpu::TextureView,
    /// GGX-prefiltered radiance, one mip level per roughness step.
    pub prefiltered: wgpu::TextureView,
    /// Irradiance over π.
    pub irradiance: wgpu::TextureView,
    /// The split-sum BRDF table: F0's scale (r) and bias (g).
    pub brdf: wgpu::TextureView,
    /// Linear filtering, wrapping round the panorama's columns.
    pub sampler: wgpu::Sampler,
}

/// The bake shader's uniform (`VeneerBake`).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct BakeUniform {
    target_size: [f32; 2],
    roughness: f32,
    samples: u32,
    source_texels: f32,
    source_levels: f32,
    irradiance_level: u32,
    padding: u32,
}

impl EnvironmentMaps {
    /// Uploads `environment` and derives its maps.
    pub fn new(
        gpu: &GpuContext,
        environment: &Environment,
    ) -> Result<EnvironmentMaps, RenderError> {
        let device = &gpu.device;
        let levels = mip_chain(environment);
        let (width, height) = environment.size();
        let source = texture(
            device,
            "environment",
            (width, height),
            levels.len() as u32,
            wgpu::TextureUsages::COPY_DST,
        );
        for (level, texels) in levels.iter().enumerate() {
            let (w, h) = (width >> level, height >> level);
            let halves: Vec<f16> = texels
                .iter()
                .flat_map(|c| [c[0], c[1], c[2], 1.0])
                .map(f16::from_f32)
                .collect();
            gpu.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &source,
                    mip_level: level as u32,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                bytemuck::cast_slice(&halves),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(w * 8),
                    rows_per_image: Some(h),
                },
                wgpu::Extent3d {
                    width: w,
                    height: h,
                    depth_or_array_layers: 1,
                },
            );
        }
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("environment"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        let source_view = source.create_view(&Default::default());
        let baker = Baker::new(
            gpu,
            &source_view,
            &sampler,
            environment,
            levels.len() as u32,
        )?;
        let prefiltered = texture(
            device,
            "environment prefiltered",
            (PREFILTERED_WIDTH, PREFILTERED_WIDTH / 2),
            PREFILTERED_LEVELS,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let irradiance = texture(
            device,
            "environment irradiance",
            (IRRADIANCE_WIDTH, IRRADIANCE_WIDTH / 2),
            1,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let brdf = texture(
            device,
            "split-sum BRDF",
            (BRDF_SIZE, BRDF_SIZE),
            1,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("environment maps"),
        });
        for level in 0..PREFILTERED_LEVELS {
            let roughness = level as f32 / (PREFILTERED_LEVELS - 1) as f32;
            baker.draw(
                gpu,
                &mut encoder,
                Pass::Prefilter,
                &prefiltered,
                level,
                roughness,
            );
        }
        baker.draw(gpu, &mut encoder, Pass::Irradiance, &irradiance, 0, 1.0);
        baker.draw(gpu, &mut encoder, Pass::Brdf, &brdf, 0, 0.0);
        gpu.queue.submit([encoder.finish()]);
        gpu.take_errors()?;
        Ok(EnvironmentMaps {
            name: environment.name.clone(),
            source: source_view,
            prefiltered: prefiltered.create_view(&Default::default()),
            irradiance: irradiance.create_view(&Default::default()),
            brdf: brdf.create_view(&Default::default()),
            sampler,
        })
    }
}

/// A sampled half-float texture of `size` with `levels` mip levels and `usage` besides.
fn texture(
    device: &wgpu::Device,
    label: &str,
    size: (u32, u32),
    levels: u32,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: FORMAT,
        usage: usage | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    })
}

/// The panorama's texels and each 2×2 box-filtered level below, down to one row.
fn mip_chain(environment: &Environment) -> Vec<Vec<[f32; 3]>> {
    let (mut width, mut height) = environment.size();
    let mut levels = vec![environment.texels().to_vec()];
    while height > 1 {
        let above = levels.last().expect("level 0 is there");
        let (w, h) = (width / 2, height / 2);
        let texel = |x: u32, y: u32| above[(y * width + x) as usize];
        let level = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                let quad = [
                    texel(2 * x, 2 * y),
                    texel(2 * x + 1, 2 * y),
                    texel(2 * x, 2 * y + 1),
                    texel(2 * x + 1, 2 * y + 1),
                ];
                [0, 1, 2].map(|c| quad.iter().map(|t| t[c]).sum::<f32>() * 0.25)
            })
            .collect();
        levels.push(level);
        (width, height) = (w, h);
    }
    levels
}

/// Which map a bake pass derives.
#[derive(Clone, Copy)]
enum Pass {
    Prefilter,
    Irradiance,
    Brdf,
}

/// The bake pipelines and what they read.
struct Baker<'a> {
    pipelines: [wgpu::RenderPipeline; 3],
    source: &'a wgpu::TextureView,
    sampler: &'a wgpu::Sampler,
    source_texels: f32,
    source_levels: u32,
    irradiance_level: u32,
}

impl<'a> Baker<'a> {
    fn new(
        gpu: &GpuContext,
        source: &'a wgpu::TextureView,
        sampler: &'a wgpu::Sampler,
        environment: &Environment,
        source_levels: u32,
    ) -> Result<Baker<'a>, RenderError> {
        let code = concat!(
            include_str!("../../../shaders/ggx.wgsl"),
            include_str!("../../../shaders/environment_bake.wgsl")
        );
        let module = gpu.shader("environment bake", code)?;
        let pipeline = |entry| {
            gpu.checked("environment bake pipeline", || {
                fullscreen_pipeline(
                    &gpu.device,
                    "environment bake",
                    &module,
                    ("veneer_bake_vertex", entry),
                    FORMAT,
                )
            })
        };
        let (width, height) = environment.size();
        Ok(Baker {
            pipelines: [
                pipeline("veneer_bake_prefilter")?,
                pipeline("veneer_bake_irradiance")?,
                pipeline("veneer_bake_brdf")?,
            ],
            source,
            sampler,
            source_texels: (width * height) as f32,
            source_levels,
            irradiance_level: (width / IRRADIANCE_SOURCE_WIDTH).max(1).ilog2(),
        })
    }

    /// Records the pass that fills mip `level` of `target`.
    fn draw(
        &self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        pass: Pass,
        target: &wgpu::Texture,
        level: u32,
        roughness: f32,
    ) {
        let device = &gpu.device;
        let (width, height) = (
            (target.width() >> level).max(1),
            (target.height() >> level).max(1),
        );
        let uniform = BakeUniform {
            target_size: [width as f32, height as f32],
            roughness,
            samples: SAMPLES,
            source_texels: self.source_texels,
            source_levels: self.source_levels as f32,
            irradiance_level: self.irradiance_level,
            padding: 0,
        };
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("environment bake"),
            size: std::mem::size_of::<BakeUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        gpu.queue
            .write_buffer(&buffer, 0, bytemuck::bytes_of(&uniform));
        let pipeline = &self.pipelines[pass as usize];
        let mut entries = vec![wgpu::BindGroupEntry {
            binding: 0,
            resource: buffer.as_entire_binding(),
        }];
        // The split-sum table depends on the BRDF alone.
        if !matches!(pass, Pass::Brdf) {
            entries.push(wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(self.source),
            });
        }
        if matches!(pass, Pass::Prefilter) {
            entries.push(wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::Sampler(self.sampler),
            });
        }
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("environment bake"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let view = target.create_view(&wgpu::TextureViewDescriptor {
            base_mip_level: level,
            mip_level_count: Some(1),
            ..Default::default()
        });
        let mut render = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("environment bake"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        render.set_pipeline(pipeline);
        render.set_bind_group(0, &group, &[]);
        render.draw(0..3, 0..1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mip_chain_halves_down_to_one_row_keeping_the_mean() {
        let environment =
            Environment::from_fn("test", 64, |d| glam::Vec3::new(1.0 + d.y, 2.0, d.x * d.x));
        let chain = mip_chain(&environment);
        assert_eq!(chain.len(), 6);
        assert_eq!(chain.last().unwrap().len(), 2);
        let mean =
            |level: &[[f32; 3]]| level.iter().map(|c| c[0]).sum::<f32>() / level.len() as f32;
        for level in &chain {
            assert!((mean(level) - mean(&chain[0])).abs() < 1e-4);
            assert!(level.iter().all(|c| c[1] == 2.0));
        }
    }
}
