//! High to low (`veneer bake --mesh LOW --from HIGH`): a tilted plane baked onto a flat
//! one gives its slope as the normal map and its rise as the height map; a high mesh
//! covering half the low one is baked with the misses reported as a share; one that
//! misses it entirely is refused and nothing is written.

use crate::support::{run_veneer, temp_dir};
use std::path::Path;

/// An OBJ of the plane y = slope·z over x in `x_range`, z from −2 to 2, at `lift`.
fn tilted_plane(path: &Path, slope: f32, x_range: (f32, f32), lift: f32) {
    let (x0, x1) = x_range;
    let corners = [(x0, -2.0), (x1, -2.0), (x1, 2.0), (x0, 2.0)];
    let mut text = String::new();
    for (x, z) in corners {
        text += &format!("v {x} {} {z}\n", lift + slope * z);
    }
    // Counter-clockwise seen from above (+y).
    text += "f 1 4 3\nf 1 3 2\n";
    std::fs::write(path, text).expect("OBJ written");
}

/// Runs a transfer of `high` onto the plane primitive into `dir`.
fn transfer(dir: &Path, high: &Path) -> std::process::Output {
    run_veneer(&[
        "bake",
        "--mesh",
        "plane",
        "--from",
        high.to_str().unwrap(),
        "--size",
        "32",
        "--cage",
        "20",
        "--out-dir",
        dir.to_str().unwrap(),
    ])
}

#[test]
fn a_tilted_plane_bakes_its_slope_and_rise_onto_a_flat_one() {
    let dir = temp_dir("high-to-low");
    let high = dir.join("tilted.obj");
    tilted_plane(&high, 0.2, (-2.0, 2.0), 0.0);
    let output = transfer(&dir, &high);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success() && !stderr.contains("warning"),
        "{stderr}"
    );
    let normal = image::open(dir.join("plane_normal.png"))
        .expect("a PNG")
        .to_rgb8();
    let height = image::open(dir.join("plane_height.png"))
        .expect("a PNG")
        .to_luma8();
    // The high normal (0, 1, −0.2) leans up the image (towards −z, where v falls).
    let length = (1.0f32 + 0.04).sqrt();
    let expected = [0.0, 0.2 / length, 1.0 / length].map(|c| (255.0 * (0.5 + 0.5 * c)).round());
    for (x, y, pixel) in normal.enumerate_pixels() {
        let got = pixel.0.map(f32::from);
        assert!(
            (0..3).all(|k| (got[k] - expected[k]).abs() <= 2.0),
            "texel ({x}, {y}): {got:?} against {expected:?}"
        );
        // Height: 0.5 on the low plane, 1 at the cage (0.2 of the bounding radius √2).
        let z = -1.0 + 2.0 * (y as f32 + 0.5) / 32.0;
        let rise = 0.2 * z / 2f32.sqrt();
        let level = (255.0 * (0.5 + 0.5 * rise / 0.2)).round();
        let got = f32::from(height.get_pixel(x, y).0[0]);
        assert!(
            (got - level).abs() <= 2.0,
            "texel ({x}, {y}): height {got} against {level}"
        );
    }
}

#[test]
fn misses_are_reported_as_a_share_and_a_total_miss_is_refused() {
    let dir = temp_dir("high-to-low-misses");
    let half = dir.join("half.obj");
    tilted_plane(&half, 0.0, (-2.0, 0.0), 0.05);
    let output = transfer(&dir, &half);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(
        stderr.contains("512 of 1024 texels (50.00%)") && stderr.contains("Raise --cage"),
        "{stderr}"
    );

    let far = dir.join("far.obj");
    tilted_plane(&far, 0.0, (-2.0, 2.0), 5.0);
    let out = temp_dir("high-to-low-refused");
    let refused = transfer(&out, &far);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success(), "{stderr}");
    assert!(
        stderr.contains("no ray") && stderr.contains("nothing was baked"),
        "{stderr}"
    );
    assert_eq!(std::fs::read_dir(&out).expect("folder").count(), 0);
}

/// One shape at two densities: a 12-segment torus takes the heights of a 192-segment
/// one, at every texel how far out of the coarse facet the true torus (radii 0.7 and
/// 0.3) lies, and normals close to the coarse mesh's own (both are smooth).
#[test]
fn a_coarse_torus_takes_the_fine_ones_heights() {
    use veneer::bake::{Format, NormalConvention, TransferMap, TransferSettings, transfer};
    use veneer::mesh_fields::{Scene, Texels};
    let dir = temp_dir("high-to-low-torus");
    let low = veneer::mesh::primitive("torus:12").expect("primitive");
    let high = veneer::mesh::primitive("torus:192").expect("primitive");
    let settings = TransferSettings {
        size: 64,
        format: Format::Png16,
        cage: 10,
        convention: NormalConvention::OpenGl,
    };
    let maps = [TransferMap::Height, TransferMap::Normal];
    let done = transfer(&low, &high, &maps, &settings, &dir.join("torus"), |_, _| {})
        .expect("the torus bakes");
    assert_eq!(done.missed_texels, 0);
    let height = image::open(dir.join("torus_height.png"))
        .expect("a PNG")
        .to_luma16();
    let normal = image::open(dir.join("torus_normal.png"))
        .expect("a PNG")
        .to_rgb16();
    let scene = Scene::new(&low);
    let texels = Texels::new(&low, &scene, 64);
    let frame = scene.frame();
    let mut largest = 0.0f64;
    for (&texel, (point, _)) in texels.texels.iter().zip(texels.points()) {
        let p = point.as_dvec3() / frame.scale + frame.centre;
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        let expected = 0.3 - ((rho - 0.7).powi(2) + p.y * p.y).sqrt();
        let (x, y) = (texel % 64, texel / 64);
        let value = f64::from(height.get_pixel(x, y).0[0]) / 65535.0;
        let baked = (value - 0.5) * 2.0 * done.cage;
        largest = largest.max((baked - expected).abs());
        let tilt = normal
            .get_pixel(x, y)
            .0
            .map(|c| f64::from(c) / 65535.0 * 2.0 - 1.0);
        assert!(tilt[2] > 0.99, "texel ({x}, {y}): normal {tilt:?}");
    }
    // The fine torus's own facets lie up to about 7·10⁻⁵ inside the true one; the
    // heights themselves reach 0.018.
    assert!(largest < 2.0e-4, "largest height error {largest}");
    assert!(
        done.heights.1 > 0.01,
        "the coarse facets lie inside: {:?}",
        done.heights
    );
}

/// The maps `graphs/baked_rock.ron` reads are what the README's command bakes today:
/// `rock:160` onto `rock:24` at 512², within one level of a fresh bake at every texel.
#[test]
fn the_baked_rock_maps_are_a_fresh_bake() {
    let dir = temp_dir("high-to-low-rock");
    let output = run_veneer(&[
        "bake",
        "--mesh",
        "rock:24",
        "--from",
        "rock:160",
        "--maps",
        "normal,height",
        "--size",
        "512",
        "--out-dir",
        dir.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success() && !stderr.contains("warning"),
        "{stderr}"
    );
    for map in ["normal", "height"] {
        let file = format!("rock-24_{map}.png");
        let fresh = image::open(dir.join(&file)).expect("a PNG").to_rgba16();
        let committed = image::open(crate::support::root("graphs/baked").join(&file))
            .expect("the committed PNG")
            .to_rgba16();
        assert_eq!(fresh.dimensions(), committed.dimensions(), "{file}");
        let largest = (fresh.as_raw().iter().zip(committed.as_raw()))
            .map(|(a, b)| a.abs_diff(*b))
            .max();
        assert!(largest <= Some(257), "{file}: texels differ by {largest:?}");
    }
}
