//! A headless wgpu device on whatever adapter the machine has.

use std::sync::{Arc, Mutex};

/// A failure to set up the GPU or to run a render: the machine has no GPU, the GPU
/// refused the work, the request is too large, or what the render needs (its mesh, the
/// mesh's fields, the image encoder) failed.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No wgpu adapter: this machine cannot render at all.
    #[error("no GPU adapter available: {0}")]
    NoAdapter(String),
    /// The adapter would not open a device.
    #[error("cannot open the GPU device: {0}")]
    Device(String),
    /// wgpu rejected a shader or pipeline, or the GPU failed or refused the work
    /// (validation, out of memory, a lost device, a failed readback).
    #[error("{0}")]
    Gpu(String),
    /// A request the render does not accept: a zero size, a timed render larger than a
    /// tile, a rectangle beyond the f32 range.
    #[error("{0}")]
    Invalid(String),
    /// The image would not fit in memory.
    #[error(
        "a {size}×{size} image needs about {} of memory, {why}; ask for a smaller size",
        crate::fsutil::gibibytes(*.bytes)
    )]
    TooLarge {
        size: u32,
        /// The bytes needed.
        bytes: u64,
        /// Why they are not to be had.
        why: String,
    },
    /// The mesh to render on could not be loaded.
    #[error(transparent)]
    Mesh(#[from] crate::mesh::MeshError),
    /// The distance fields of the mesh `mesh` could not be solved.
    #[error("{mesh}: {error}")]
    Fields {
        mesh: String,
        #[source]
        error: crate::geodesic::FieldError,
    },
    /// The mesh fields of the mesh `mesh` could not be computed.
    #[error("{mesh}: {error}")]
    MeshFields {
        mesh: String,
        #[source]
        error: crate::mesh_fields::MeshFieldError,
    },
    /// The image could not be encoded.
    #[error("cannot encode PNG: {0}")]
    Encode(#[source] image::ImageError),
    /// Whoever took the rendered rows stopped taking them (a bake's writer).
    #[error("{0}")]
    Stopped(&'static str),
}

/// A wgpu device and queue without a window.
pub struct GpuContext {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    /// Errors wgpu raised outside any error scope (wgpu's default is to panic on them).
    uncaptured: Arc<Mutex<Vec<String>>>,
    /// The procedural sky's lighting maps, derived when first asked for.
    sky: Mutex<Option<Arc<super::EnvironmentMaps>>>,
}

impl GpuContext {
    /// Opens the best adapter of the backends in `WGPU_BACKEND` (default: all): a real
    /// GPU when there is one, otherwise a software rasteriser (lavapipe, llvmpipe).
    pub fn new() -> Result<GpuContext, RenderError> {
        Self::with_limits(|limits| limits)
    }

    /// [`GpuContext::new`] with the device's limits narrowed by `narrow` (given what the
    /// adapter offers), to see how Veneer copes with a smaller device than this one.
    pub fn with_limits(
        narrow: impl FnOnce(wgpu::Limits) -> wgpu::Limits,
    ) -> Result<GpuContext, RenderError> {
        Self::open(
            wgpu::InstanceDescriptor::new_without_display_handle_from_env(),
            narrow,
        )
    }

    /// Opens the best adapter of `backends` alone, whatever `WGPU_BACKEND` says (for
    /// checks that must hold on Vulkan and GL alike).
    pub fn on_backends(backends: wgpu::Backends) -> Result<GpuContext, RenderError> {
        let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        descriptor.backends = backends;
        Self::open(descriptor, |limits| limits)
    }

    fn open(
        descriptor: wgpu::InstanceDescriptor,
        narrow: impl FnOnce(wgpu::Limits) -> wgpu::Limits,
    ) -> Result<GpuContext, RenderError> {
        let instance = wgpu::Instance::new(descriptor);
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        }))
        .map_err(|error| RenderError::NoAdapter(error.to_string()))?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("veneer"),
            // Timestamps where the adapter has them, for timings of the GPU's work alone.
            required_features: adapter.features() & wgpu::Features::TIMESTAMP_QUERY,
            required_limits: narrow(
                wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits()),
            ),
            ..Default::default()
        }))
        .map_err(|error| RenderError::Device(error.to_string()))?;
        let uncaptured = Arc::new(Mutex::new(Vec::new()));
        let errors = Arc::clone(&uncaptured);
        device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
            if let Ok(mut errors) = errors.lock() {
                errors.push(error.to_string());
            }
        }));
        Ok(GpuContext {
            adapter,
            device,
            queue,
            uncaptured,
            sky: Mutex::default(),
        })
    }

    /// A context on a device opened elsewhere (the editor's), whose own handler keeps
    /// receiving the errors raised outside error scopes.
    pub fn on_device(
        adapter: wgpu::Adapter,
        device: wgpu::Device,
        queue: wgpu::Queue,
    ) -> GpuContext {
        GpuContext {
            adapter,
            device,
            queue,
            uncaptured: Arc::default(),
            sky: Mutex::default(),
        }
    }

    /// The lighting maps of the procedural sky, the default environment of
    /// metallic-roughness materials (derived on this device the first time).
    pub fn sky(&self) -> Result<Arc<super::EnvironmentMaps>, RenderError> {
        let mut sky = self
            .sky
            .lock()
            .map_err(|_| RenderError::Gpu("the sky's maps were lost to a panic".into()))?;
        if let Some(maps) = sky.as_ref() {
            return Ok(Arc::clone(maps));
        }
        let maps = Arc::new(super::EnvironmentMaps::new(
            self,
            &super::Environment::sky(),
        )?);
        *sky = Some(Arc::clone(&maps));
        Ok(maps)
    }

    /// Fails with the errors wgpu raised outside error scopes since the last call (out of
    /// memory, a limit passed), so that a broken render is an error instead of an image.
    pub fn take_errors(&self) -> Result<(), RenderError> {
        let errors = match self.uncaptured.lock() {
            Ok(mut errors) => std::mem::take(&mut *errors),
            Err(_) => return Err(RenderError::Gpu("a GPU error handler panicked".into())),
        };
        match errors.as_slice() {
            [] => Ok(()),
            [first, ..] => Err(RenderError::Gpu(format!(
                "the GPU refused the work: {first}{}",
                if errors.len() > 1 {
                    format!(" (and {} more errors)", errors.len() - 1)
                } else {
                    String::new()
                }
            ))),
        }
    }

    /// "name (backend)" of the adapter, as recorded next to golden images.
    pub fn adapter_description(&self) -> String {
        let info = self.adapter.get_info();
        format!("{} ({:?})", info.name, info.backend)
    }

    /// Compiles WGSL into a shader module, turning validation errors into a `RenderError`.
    pub fn shader(&self, label: &str, source: &str) -> Result<wgpu::ShaderModule, RenderError> {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
        match pollster::block_on(scope.pop()) {
            Some(error) => Err(RenderError::Gpu(format!(
                "shader '{label}' rejected by wgpu: {error}"
            ))),
            None => Ok(module),
        }
    }

    /// Runs `f`, returning any validation error wgpu raised meanwhile.
    pub fn checked<T>(&self, what: &str, f: impl FnOnce() -> T) -> Result<T, RenderError> {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let value = f();
        match pollster::block_on(scope.pop()) {
            Some(error) => Err(RenderError::Gpu(format!("{what}: {error}"))),
            None => Ok(value),
        }
    }
}
