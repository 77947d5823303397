//! `--params uniform`: the exposed parameters as one named uniform struct. Its layout
//! is checked against naga's, and a wgpu program that sets the parameters by name,
//! through the JSON description's offsets, draws what `--set` draws.

use crate::support::{gpu, root, run_veneer, temp_dir};
use std::collections::BTreeMap;

/// The fragment's surface over the wood preset's preview square, a full-screen
/// triangle's worth, and the exported module's fragment entry point after it.
const VERTEX: &str = r#"
struct VeneerVertexOutput {
    @builtin(position) clip: vec4f,
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) uv: vec2f,
    @location(3) fields: vec4f,
}

@vertex
fn test_vertex(@builtin(vertex_index) index: u32) -> VeneerVertexOutput {
    let uv = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
    var out: VeneerVertexOutput;
    out.clip = vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
    out.position = vec3f(22.0 + 9.0 * uv.x, 2.0, 18.0 + 9.0 * uv.y);
    out.normal = vec3f(0.0, 1.0, 0.0);
    out.uv = uv;
    out.fields = vec4f(0.0);
    return out;
}
"#;

/// The size of the test image.
const SIZE: u32 = 32;

/// `veneer compile graphs/wood.ron` with `args`, as text.
fn compiled(args: &[&str]) -> String {
    let mut all = vec!["compile", "graphs/wood.ron"];
    all.extend(args);
    let output = run_veneer(&all);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("text")
}

/// Draws `material` (a module from `veneer compile`) with the export's fragment entry,
/// binding `parameters` (the bytes of `VeneerParameters`) when there are some; returns
/// the RGBA floats.
fn draw(material: &str, parameters: Option<&[u8]>) -> Vec<f32> {
    let gpu = gpu();
    let device = &gpu.device;
    let entry = std::fs::read_to_string(root("shaders/export_entry.wgsl")).expect("reads");
    let source = format!("{material}\n{entry}\n{VERTEX}");
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("parameter export test"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let format = wgpu::TextureFormat::Rgba32Float;
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: None,
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("test_vertex"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("veneer_fragment"),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    });
    let uniform = |bytes: &[u8]| {
        use wgpu::util::DeviceExt;
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents: bytes,
            usage: wgpu::BufferUsages::UNIFORM,
        })
    };
    let frame = uniform(&[0u8; 16]);
    let bind = |group: u32, buffer: &wgpu::Buffer| {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(group),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            }],
        })
    };
    let frame_group = bind(0, &frame);
    let parameter_group = parameters.map(|bytes| bind(1, &uniform(bytes)));
    let target = device.create_texture(&wgpu::TextureDescriptor {
        label: None,
        size: wgpu::Extent3d {
            width: SIZE,
            height: SIZE,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let view = target.create_view(&Default::default());
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: None,
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
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &frame_group, &[]);
        if let Some(group) = &parameter_group {
            pass.set_bind_group(1, group, &[]);
        }
        pass.draw(0..3, 0..1);
    }
    gpu.queue.submit([encoder.finish()]);
    let bytes = veneer::render::read_texture(gpu, &target, 16).expect("reads back");
    bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect()
}

/// The bytes of `VeneerParameters` with `values` (by parameter name) written at the
/// offsets the description gives, every other parameter at its default.
fn parameter_bytes(description: &serde_json::Value, values: &BTreeMap<&str, Vec<f32>>) -> Vec<u8> {
    let size = description["size"].as_u64().expect("size") as usize;
    let mut bytes = vec![0u8; size];
    for parameter in description["parameters"].as_array().expect("parameters") {
        let name = parameter["name"].as_str().expect("name");
        let components: Vec<f32> = match values.get(name) {
            Some(value) => value.clone(),
            None => match &parameter["default"] {
                serde_json::Value::Array(list) => {
                    list.iter().map(|x| x.as_f64().unwrap() as f32).collect()
                }
                x => vec![x.as_f64().expect("a number") as f32],
            },
        };
        let offset = parameter["offset"].as_u64().expect("offset") as usize;
        for (k, x) in components.iter().enumerate() {
            bytes[offset + 4 * k..offset + 4 * k + 4].copy_from_slice(&x.to_le_bytes());
        }
    }
    bytes
}

#[test]
fn the_uniform_layout_is_the_one_naga_computes() {
    let source = compiled(&["--params", "uniform"]);
    let description: serde_json::Value =
        serde_json::from_str(&compiled(&["--describe"])).expect("JSON");
    let module = naga::front::wgsl::parse_str(&source).expect("parses");
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("lays out");
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some("VeneerParameters"))
        .expect("the struct");
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        panic!("VeneerParameters is a struct");
    };
    assert_eq!(u64::from(*span), description["size"].as_u64().unwrap());
    assert_eq!(layouter[handle].size, *span);
    let described = description["parameters"].as_array().unwrap();
    assert_eq!(members.len(), described.len());
    for (member, entry) in members.iter().zip(described) {
        assert_eq!(member.name.as_deref(), entry["member"].as_str());
        assert_eq!(u64::from(member.offset), entry["offset"].as_u64().unwrap());
    }
    // The JSON beside an export is the same description.
    let dir = temp_dir("parameter-export");
    let out = dir.join("wood.wgsl");
    let output = run_veneer(&[
        "compile",
        "graphs/wood.ron",
        "--params",
        "uniform",
        "-o",
        &out.to_string_lossy(),
    ]);
    assert!(output.status.success());
    let beside: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("wood.parameters.json")).unwrap()).unwrap();
    assert_eq!(beside, description);
}

#[test]
fn parameters_set_by_name_draw_what_set_draws() {
    let named = compiled(&["--params", "uniform"]);
    let description: serde_json::Value =
        serde_json::from_str(&compiled(&["--describe"])).expect("JSON");
    let defaults = draw(
        &named,
        Some(&parameter_bytes(&description, &BTreeMap::new())),
    );
    let baked = draw(&compiled(&[]), None);
    let worst = |a: &[f32], b: &[f32]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0f32, f32::max)
    };
    // Constant folding computes some baked values on the CPU: a last-bit difference.
    assert!(
        worst(&defaults, &baked) < 1e-4,
        "{}",
        worst(&defaults, &baked)
    );

    let values: BTreeMap<&str, Vec<f32>> = [
        ("ring_frequency", vec![0.7]),
        ("late_wood", vec![0.9, 0.2, 0.1]),
    ]
    .into_iter()
    .collect();
    let set = draw(&named, Some(&parameter_bytes(&description, &values)));
    let by_set = draw(
        &compiled(&[
            "--set",
            "ring_frequency=0.7",
            "--set",
            "late_wood=0.9,0.2,0.1",
        ]),
        None,
    );
    assert!(worst(&set, &by_set) < 1e-4, "{}", worst(&set, &by_set));
    assert!(
        worst(&set, &defaults) > 0.05,
        "the parameters change the image"
    );
}
