//! Image-based lighting of metallic-roughness materials, on every software adapter the
//! machine has (lavapipe through Vulkan, llvmpipe through GL): a white furnace, and
//! renders against a hand-written Monte Carlo integral of the full GGX BRDF over the
//! environment.

use glam::{DVec3, Vec3};
use std::sync::Arc;
use veneer::graph::{Graph, NodeKind, Shading, Value};
use veneer::render::{
    Backdrop, Environment, GpuContext, MeshLook, MeshView, ToneMap, View, render_material_with,
};

/// Contexts on each backend with an adapter here; on CI (`CI` set) both must be there.
fn contexts() -> Vec<(&'static str, GpuContext)> {
    let found: Vec<_> = [
        ("Vulkan", wgpu::Backends::VULKAN),
        ("GL", wgpu::Backends::GL),
    ]
    .into_iter()
    .filter_map(|(name, backends)| Some((name, GpuContext::on_backends(backends).ok()?)))
    .collect();
    let needed = if std::env::var_os("CI").is_some() {
        2
    } else {
        1
    };
    assert!(
        found.len() >= needed,
        "only {} backends: {:?}",
        found.len(),
        found.iter().map(|f| f.0).collect::<Vec<_>>()
    );
    found
}

/// A metallic-roughness material of constant base colour, metallic and roughness.
fn material(base: (f64, f64, f64), metallic: f64, roughness: f64) -> Graph {
    let mut graph = Graph {
        shading: Shading::MetallicRoughness,
        ..Graph::default()
    };
    let node = graph.add("material", NodeKind::Material);
    graph.set_input(node, "albedo", Value::Color(base.0, base.1, base.2));
    graph.set_input(node, "metallic", Value::Float(metallic));
    graph.set_input(node, "roughness", Value::Float(roughness));
    graph
}

const SIZE: u32 = 96;

/// The sphere under `environment` with `key_light`, no tone mapping, RGBA rows.
fn render(
    gpu: &GpuContext,
    graph: &Graph,
    environment: &Arc<Environment>,
    key_light: f32,
) -> Vec<u8> {
    let compiled = veneer::codegen::compile(graph, &Default::default()).expect("compiles");
    let look = MeshLook {
        tone_map: ToneMap::None,
        environment: Some(Arc::clone(environment)),
        key_light,
        backdrop: Backdrop::Colour,
        ..MeshLook::default()
    };
    render_material_with(
        gpu,
        &compiled,
        &View::Mesh(Some("sphere".into())),
        SIZE,
        0.0,
        look,
    )
    .expect("renders")
    .image
    .pixels
}

/// Each pixel whose centre sees the unit sphere well inside its outline (clear of the
/// multisampled edge): its index, the unit normal there and the unit direction to the eye.
fn sphere_pixels() -> Vec<(usize, DVec3, DVec3)> {
    let view = MeshView::for_preview(&Default::default());
    let mut pixels = Vec::new();
    for row in 0..SIZE {
        for column in 0..SIZE {
            let ndc = [
                (column as f32 + 0.5) / SIZE as f32 * 2.0 - 1.0,
                1.0 - (row as f32 + 0.5) / SIZE as f32 * 2.0,
            ];
            let (origin, direction) = view.ray(1.0, ndc);
            let (origin, direction) = (origin.as_dvec3(), direction.as_dvec3());
            let closest = -origin.dot(direction);
            let miss = (origin + direction * closest).length();
            if miss < 0.95 {
                let hit = origin + direction * (closest - (1.0 - miss * miss).sqrt());
                pixels.push(((row * SIZE + column) as usize, hit.normalize(), -direction));
            }
        }
    }
    pixels
}

/// The sRGB encoding of linear `value`, as 8 bits show it (before rounding).
fn srgb(value: f64) -> f64 {
    let c = value.clamp(0.0, 1.0);
    255.0
        * if c <= 0.0031308 {
            12.92 * c
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        }
}

#[test]
fn a_white_rough_dielectric_under_a_uniform_white_environment_shows_the_environment() {
    // White furnace: whatever reflects specularly is missing from the diffuse part, so
    // a white dielectric returns the light it gets. Radiance 0.5 keeps clear of clipping.
    let environment = Arc::new(Environment::from_fn("furnace", 64, |_| Vec3::splat(0.5)));
    let expected = srgb(0.5);
    for (backend, gpu) in contexts() {
        for roughness in [1.0, 0.6, 0.25] {
            let pixels = render(
                &gpu,
                &material((1.0, 1.0, 1.0), 0.0, roughness),
                &environment,
                0.0,
            );
            let worst = sphere_pixels()
                .iter()
                .flat_map(|(index, _, _)| &pixels[index * 4..index * 4 + 3])
                .map(|&value| (f64::from(value) - expected).abs())
                .fold(0.0, f64::max);
            // 2/255 in display values is about 1% of the linear radiance.
            assert!(
                worst <= 2.0,
                "{backend}, roughness {roughness}: off by {worst}/255"
            );
        }
    }
}

/// A smooth environment with structure: a sky brighter overhead, a dim ground and a broad
/// bright lobe low on the left-front.
fn studio(direction: Vec3) -> Vec3 {
    let d = direction.as_dvec3();
    let sky = DVec3::new(0.25, 0.3, 0.4) * (1.0 + d.y.max(0.0)) + DVec3::splat(0.08);
    let lobe = DVec3::new(0.9, 0.8, 0.6)
        * (-(1.0 - d.dot(DVec3::new(-0.6, 0.3, 0.74).normalize())) * 3.0).exp();
    (sky + lobe).as_vec3()
}

/// The Hammersley point `i` of `n`.
fn hammersley(i: u32, n: u32) -> (f64, f64) {
    (
        f64::from(i) / f64::from(n),
        f64::from(i.reverse_bits()) / 4_294_967_296.0,
    )
}

/// Two unit vectors completing `n` to an orthonormal frame.
fn frame(n: DVec3) -> (DVec3, DVec3) {
    let up = if n.z.abs() < 0.999 {
        DVec3::Z
    } else {
        DVec3::X
    };
    let t = up.cross(n).normalize();
    (t, n.cross(t))
}

/// glTF 2.0's metallic-roughness BRDF (appendix B): Lambert diffuse weighted by
/// 1 − Fresnel, Trowbridge-Reitz distribution, Smith height-correlated visibility,
/// Schlick Fresnel.
struct Brdf {
    base: DVec3,
    metallic: f64,
    alpha: f64,
}

impl Brdf {
    fn fresnel(&self, v_h: f64) -> DVec3 {
        let f0 = DVec3::splat(0.04).lerp(self.base, self.metallic);
        f0 + (DVec3::ONE - f0) * (1.0 - v_h).max(0.0).powi(5)
    }

    fn visibility(&self, n_v: f64, n_l: f64) -> f64 {
        let a2 = self.alpha * self.alpha;
        0.5 / (n_l * (n_v * n_v * (1.0 - a2) + a2).sqrt()
            + n_v * (n_l * n_l * (1.0 - a2) + a2).sqrt())
    }

    fn distribution(&self, n_h: f64) -> f64 {
        let a2 = self.alpha * self.alpha;
        let d = n_h * n_h * (a2 - 1.0) + 1.0;
        a2 / (std::f64::consts::PI * d * d)
    }

    /// Diffuse and specular parts of the BRDF times n·l, for light from `l`.
    fn parts(&self, n: DVec3, v: DVec3, l: DVec3) -> (DVec3, DVec3) {
        let h = (v + l).normalize();
        let (n_l, n_v) = (n.dot(l).max(0.0), n.dot(v).max(1e-4));
        let fresnel = self.fresnel(v.dot(h).max(0.0));
        let diffuse =
            (DVec3::ONE - fresnel) * (1.0 - self.metallic) * self.base / std::f64::consts::PI;
        let specular = fresnel * self.distribution(n.dot(h).max(0.0)) * self.visibility(n_v, n_l);
        (diffuse * n_l, specular * n_l)
    }

    /// Light leaving towards `v` under `environment` and the key light: the diffuse part
    /// integrated by cosine-weighted samples, the specular part by GGX-distributed half
    /// vectors, `samples` of each.
    fn radiance(&self, n: DVec3, v: DVec3, key: (DVec3, f64), samples: u32) -> DVec3 {
        let (t, b) = frame(n);
        let environment = |l: DVec3| studio(l.as_vec3()).as_dvec3();
        let mut total = DVec3::ZERO;
        for i in 0..samples {
            let (u1, u2) = hammersley(i, samples);
            let phi = 2.0 * std::f64::consts::PI * u1;
            // Cosine-weighted: pdf n·l / π.
            let (r, z) = (u2.sqrt(), (1.0 - u2).sqrt());
            let l = (t * phi.cos() * r + b * phi.sin() * r + n * z).normalize();
            let (diffuse, _) = self.parts(n, v, l);
            total += diffuse * environment(l) * std::f64::consts::PI / z.max(1e-9);
            // GGX half vectors: pdf of l = D n·h / (4 v·h).
            let cos_theta = ((1.0 - u2) / (1.0 + (self.alpha * self.alpha - 1.0) * u2)).sqrt();
            let sin_theta = (1.0 - cos_theta * cos_theta).sqrt();
            let h =
                (t * phi.cos() * sin_theta + b * phi.sin() * sin_theta + n * cos_theta).normalize();
            let l = 2.0 * v.dot(h) * h - v;
            if n.dot(l) > 0.0 {
                let (_, specular) = self.parts(n, v, l);
                let pdf = self.distribution(n.dot(h)) * n.dot(h) / (4.0 * v.dot(h));
                total += specular * environment(l) / pdf;
            }
        }
        let (diffuse, specular) = self.parts(n, v, key.0);
        total / f64::from(samples) + (diffuse + specular) * key.1
    }
}

#[test]
fn metallic_roughness_renders_match_a_hand_written_ggx_integral_of_the_environment() {
    let environment = Arc::new(Environment::from_fn("studio", 512, studio));
    let view = MeshView::for_preview(&Default::default());
    let key = (
        Vec3::from(view.light).normalize().as_dvec3(),
        f64::from(view.key_light),
    );
    let cases = [
        ((0.8, 0.5, 0.3), 0.0, 0.8),
        ((0.9, 0.75, 0.4), 1.0, 0.35),
        ((0.5, 0.6, 0.7), 0.3, 0.55),
        ((0.95, 0.95, 0.95), 1.0, 0.15),
    ];
    let pixels = sphere_pixels();
    for (backend, gpu) in contexts() {
        for (base, metallic, roughness) in cases {
            let image = render(
                &gpu,
                &material(base, metallic, roughness),
                &environment,
                view.key_light,
            );
            let brdf = Brdf {
                base: DVec3::new(base.0, base.1, base.2),
                metallic,
                alpha: (roughness * roughness).max(1e-3),
            };
            let (mut sum, mut count, mut worst) = (0.0, 0, 0.0f64);
            // Within 1.5/255 on average and 12/255 at worst (where the key light's
            // highlight meets the mesh's interpolated normals), every fourth pixel, away
            // from grazing angles (where the split sum's n = v assumption is furthest
            // off) and from clipping.
            for (index, n, v) in pixels
                .iter()
                .step_by(4)
                .filter(|(_, n, v)| n.dot(*v) > 0.25)
            {
                let expected = brdf.radiance(*n, *v, key, 1024);
                if expected.max_element() > 0.95 {
                    continue;
                }
                for channel in 0..3 {
                    let error =
                        (f64::from(image[index * 4 + channel]) - srgb(expected[channel])).abs();
                    sum += error;
                    worst = worst.max(error);
                    count += 1;
                }
            }
            let mean = sum / f64::from(count);
            println!(
                "{backend} {base:?} metallic {metallic} roughness {roughness}: mean {mean:.2}/255, worst {worst:.1}/255 over {count} values"
            );
            assert!(count > 300, "{count} values compared");
            assert!(
                mean <= 1.5 && worst <= 12.0,
                "{backend} {base:?} metallic {metallic} roughness {roughness}: mean {mean:.2}/255, worst {worst:.1}/255"
            );
        }
    }
}

#[test]
fn the_cli_lights_with_a_panorama_file_and_refuses_what_is_not_one() {
    let dir = crate::support::temp_dir("environment_cli");
    let render = |name: &str, extra: &[&str]| {
        let output = dir.join(name);
        let graph = crate::support::root("graphs/marble_polished.ron");
        let mut args = vec![
            "render",
            graph.to_str().unwrap(),
            "--size",
            "32",
            "-o",
            output.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        (crate::support::run_veneer(&args), output)
    };
    let (sky, sky_png) = render("sky.png", &[]);
    assert!(
        sky.status.success(),
        "{}",
        String::from_utf8_lossy(&sky.stderr)
    );
    let panorama = crate::support::root("tests/environments/red_wall.hdr");
    let (lit, lit_png) = render("lit.png", &["--environment", panorama.to_str().unwrap()]);
    assert!(
        lit.status.success(),
        "{}",
        String::from_utf8_lossy(&lit.stderr)
    );
    assert_ne!(
        std::fs::read(&sky_png).unwrap(),
        std::fs::read(&lit_png).unwrap()
    );
    let not_a_panorama = crate::support::root("tests/snapshots/wood.png");
    let (refused, refused_png) = render(
        "refused.png",
        &["--environment", not_a_panorama.to_str().unwrap()],
    );
    let message = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(1), "{message}");
    assert!(
        message.contains("wood.png") && message.contains(".hdr or .exr"),
        "{message}"
    );
    assert!(
        !refused_png.exists(),
        "nothing is written for a refused environment"
    );
    let (negative, _) = render("negative.png", &["--key-light", "-1"]);
    assert_eq!(negative.status.code(), Some(1));
}
