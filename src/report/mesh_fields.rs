//! The report's mesh-field section: ambient occlusion against ray count and adaptive
//! sampling (against a 4,096-ray reference), mean curvature on a sphere and principal
//! curvatures on a torus (against their analytic values), convexity against the radius
//! it is measured at on a sphere, and thickness on a shell of known wall.

use super::measure::median_of;
use super::plot::{Plot, Series};
use super::table::{Table, number};
use super::{Context, Section};
use crate::geodesic::welded_for_distances;
use crate::mesh_fields::{self, Sampling, Scene};
use std::time::Instant;

/// The rays per vertex occlusion is measured at, and the reference's.
const RAYS: [u32; 4] = [4, 16, 64, 256];
const REFERENCE_RAYS: u32 = 4096;

/// The wall of the shell thickness is measured on (outer radius 1).
const SHELL_INNER: f32 = 0.9;

/// `work`'s result and the median of its wall times over `runs` runs, in milliseconds.
fn timed<T>(runs: usize, mut work: impl FnMut() -> T) -> (T, f64) {
    let mut times = Vec::with_capacity(runs);
    let mut result = None;
    for _ in 0..runs.max(1) {
        let started = Instant::now();
        result = Some(work());
        times.push(started.elapsed().as_secs_f64() * 1e3);
    }
    (result.expect("at least one run"), median_of(&times))
}

/// Mean and largest of `errors`.
fn mean_and_largest(errors: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut sum, mut count, mut largest) = (0.0, 0usize, 0.0f64);
    for error in errors {
        sum += error;
        count += 1;
        largest = largest.max(error);
    }
    (sum / count.max(1) as f64, largest)
}

/// A row of the table.
struct Row<'a> {
    field: &'a str,
    mesh: &'a str,
    setting: String,
    errors: (f64, f64),
    ms: f64,
    rays: Option<f64>,
}

/// Adds `row` to `table` and its time and mean error to `series`.
fn record(table: &mut Table, series: &mut Series, row: Row) {
    series.points.push((row.ms, row.errors.0));
    table.push(row.cells());
}

impl Row<'_> {
    fn cells(self) -> Vec<String> {
        vec![
            self.field.to_string(),
            self.mesh.to_string(),
            self.setting,
            number(self.errors.0, 3),
            number(self.errors.1, 3),
            number(self.ms, 3),
            self.rays
                .map_or_else(|| "—".to_string(), |rays| number(rays, 3)),
        ]
    }
}

/// Occlusion at each ray count and adaptively, against the reference, on `name`.
fn occlusion_rows(ctx: &Context, name: &str, table: &mut Table) -> Result<Vec<Series>, String> {
    let mesh = crate::mesh::primitive(name).ok_or("primitive")?;
    let scene = Scene::new(&mesh);
    let sampling = |samples, tolerance| Sampling {
        samples,
        distance: 0.5,
        tolerance,
    };
    let open = |sampling| mesh_fields::occlusion(&scene, sampling, |_, _| {});
    let reference: Vec<f32> = open(sampling(REFERENCE_RAYS, None))
        .iter()
        .map(|e| e.open)
        .collect();
    let mut fixed = Series {
        name: "occlusion, fixed rays".into(),
        points: Vec::new(),
        joined: true,
    };
    let mut adaptive = Series {
        name: "occlusion, adaptive ±0.05".into(),
        points: Vec::new(),
        joined: false,
    };
    let variants = RAYS
        .iter()
        .map(|&rays| (format!("{rays} rays"), sampling(rays, None)))
        .chain([(
            "adaptive ±0.05 up to 256 rays".to_string(),
            sampling(256, Some(0.05)),
        )]);
    for (setting, variant) in variants {
        let (estimates, ms) = timed(ctx.repetitions.min(3), || open(variant));
        let errors = mean_and_largest(
            estimates
                .iter()
                .zip(&reference)
                .map(|(e, r)| f64::from((e.open - r).abs())),
        );
        let rays = estimates.iter().map(|e| f64::from(e.rays)).sum::<f64>()
            / estimates.len().max(1) as f64;
        match variant.tolerance {
            Some(_) => adaptive.points.push((ms, errors.0)),
            None => fixed.points.push((ms, errors.0)),
        }
        table.push(
            Row {
                field: "ambient occlusion",
                mesh: name,
                setting,
                errors,
                ms,
                rays: Some(rays),
            }
            .cells(),
        );
    }
    Ok(vec![fixed, adaptive])
}

/// The (rays per texel, pooling radius) texel bakes of occlusion are measured at.
const TEXEL_VARIANTS: [(u32, u32); 8] = [
    (4, 0),
    (16, 0),
    (64, 0),
    (256, 0),
    (4, 2),
    (8, 2),
    (16, 2),
    (8, 3),
];

/// Occlusion baked per texel of `name`'s UV layout at `size`², with each variant's rays
/// and pooling, against the reference's rays at every texel alone.
fn texel_occlusion_rows(
    repetitions: usize,
    name: &str,
    size: u32,
    table: &mut Table,
) -> Result<Series, String> {
    let mesh = (crate::mesh::primitive(name).ok_or("primitive")?).with_uv_layout(size);
    let scene = Scene::new(&mesh);
    let texels = mesh_fields::Texels::new(&mesh, &scene, size);
    let open = |samples| {
        let sampling = Sampling {
            samples,
            distance: 0.5,
            tolerance: None,
        };
        texels.occlusion(&scene, sampling, |_, _| {})
    };
    let reference = open(REFERENCE_RAYS);
    let mut series = Series {
        name: format!("occlusion per texel, {size}²"),
        points: Vec::new(),
        joined: false,
    };
    for (rays, pooling) in TEXEL_VARIANTS {
        let (values, ms) = timed(repetitions.min(3), || texels.pooled(&open(rays), pooling));
        let errors = mean_and_largest(
            (values.iter().zip(&reference)).map(|(v, r)| f64::from((v - r).abs())),
        );
        record(
            table,
            &mut series,
            Row {
                field: "ambient occlusion per texel",
                mesh: &format!("{name}, {size}² texels"),
                setting: match pooling {
                    0 => format!("{rays} rays alone"),
                    _ => format!("{rays} rays pooled over ±{pooling} texels"),
                },
                errors,
                ms,
                rays: Some(f64::from(rays)),
            },
        );
    }
    Ok(series)
}

/// Mean curvature on a sphere, principal curvatures on a torus and convexity at three
/// radii on a sphere, each against its analytic value (relative errors).
fn curvature_rows(ctx: &Context, detail: u32, table: &mut Table) -> Result<Series, String> {
    let mut series = Series {
        name: "curvature".into(),
        points: Vec::new(),
        joined: false,
    };
    let sphere_name = format!("sphere:{detail}");
    let (sphere, _) =
        welded_for_distances(&crate::mesh::primitive(&sphere_name).ok_or("primitive")?);
    let (curvatures, ms) = timed(ctx.repetitions, || mesh_fields::curvatures(&sphere));
    let errors = mean_and_largest(curvatures.mean.iter().map(|h| (h - 1.0).abs()));
    record(
        table,
        &mut series,
        Row {
            field: "mean curvature",
            mesh: &sphere_name,
            setting: "against 1/r".into(),
            errors,
            ms,
            rays: None,
        },
    );
    let torus_name = format!("torus 0.7/0.3 {}×{}", 4 * detail, 2 * detail);
    let (torus, _) = welded_for_distances(&crate::mesh::torus(0.7, 0.3, 4 * detail, 2 * detail));
    let (curvatures, ms) = timed(ctx.repetitions, || mesh_fields::curvatures(&torus));
    let errors = mean_and_largest(torus.positions.iter().enumerate().map(|(v, p)| {
        let [x, _, z] = p.map(f64::from);
        let cos = ((x * x + z * z).sqrt() - 0.7) / 0.3;
        let (tube, around) = (1.0 / 0.3, cos / (0.7 + 0.3 * cos));
        let (k1, k2) = curvatures.principal(v);
        ((k1 - tube).abs() / tube).max((k2 - around).abs() / tube.max(around.abs()))
    }));
    record(
        table,
        &mut series,
        Row {
            field: "principal curvatures",
            mesh: &torus_name,
            setting: "against 1/0.3 and cos v/(0.7 + 0.3 cos v)".into(),
            errors,
            ms,
            rays: None,
        },
    );
    for radius in [0.05, 0.2, 0.5] {
        let (convexity, ms) = timed(ctx.repetitions, || {
            mesh_fields::convexity(&sphere, radius).map_err(|e| e.to_string())
        });
        let errors = mean_and_largest(convexity?.iter().map(|c| (c - radius).abs() / radius));
        record(
            table,
            &mut series,
            Row {
                field: "convexity",
                mesh: &sphere_name,
                setting: format!("radius {radius}: against radius/r"),
                errors,
                ms,
                rays: None,
            },
        );
    }
    Ok(series)
}

/// Thickness of a shell of wall 0.1 at two ray counts, from its outer side.
fn thickness_rows(ctx: &Context, detail: u32, table: &mut Table) -> Result<Series, String> {
    let shell = crate::mesh::shell(SHELL_INNER, 2 * detail, detail);
    let scene = Scene::new(&shell);
    let wall = f64::from(1.0 - SHELL_INNER);
    let mesh = format!(
        "shell 1/{SHELL_INNER} ({} triangles)",
        shell.triangle_count()
    );
    let mut series = Series {
        name: "thickness".into(),
        points: Vec::new(),
        joined: true,
    };
    for rays in [16, 64] {
        let (values, ms) = timed(ctx.repetitions.min(3), || {
            mesh_fields::thickness(&scene, rays, 1.0, |_, _| {})
        });
        let errors = mean_and_largest(values.iter().map(|&t| (f64::from(t) - wall).abs() / wall));
        record(
            table,
            &mut series,
            Row {
                field: "thickness",
                mesh: &mesh,
                setting: format!("{rays} rays: against the wall"),
                errors,
                ms,
                rays: Some(f64::from(rays)),
            },
        );
    }
    Ok(series)
}

/// The mesh-field section.
pub fn mesh_fields(ctx: &Context, quick: bool) -> Result<Section, String> {
    let mut table = Table::new(&[
        "field",
        "mesh",
        "setting",
        "mean error",
        "largest error",
        "ms",
        "rays per point",
    ]);
    let (occlusion_mesh, detail) = if quick {
        ("torus:24", 24)
    } else {
        ("torus:96", 64)
    };
    let mut series = occlusion_rows(ctx, occlusion_mesh, &mut table)?;
    (ctx.progress)();
    let texel_size = if quick { 64 } else { 384 };
    series.push(texel_occlusion_rows(
        ctx.repetitions,
        "genus2",
        texel_size,
        &mut table,
    )?);
    (ctx.progress)();
    series.push(curvature_rows(ctx, detail, &mut table)?);
    (ctx.progress)();
    series.push(thickness_rows(ctx, detail, &mut table)?);
    (ctx.progress)();
    Ok(Section {
        title: "Mesh fields: error against time".into(),
        text: format!(
            "Ambient occlusion (rays up to half the bounding radius) against {REFERENCE_RAYS} rays per vertex, absolute errors, on all cores; adaptive sampling stops a vertex once its 95% interval is narrower than ±0.05, checked every 16 rays. Occlusion per texel is a bake into genus2's atlas at {texel_size}² against {REFERENCE_RAYS} rays at every texel alone: few rays per texel, pooled with the neighbours on the same surface, against more rays and no pooling (its error includes the pooling's blur). Curvatures and convexity are relative errors against the analytic values (a unit sphere's mean curvature is 1; convexity at radius ρ reads ρ there); thickness is the relative error against a 0.1 wall, from both faces of a hollow ball. Occlusion and thickness times are medians of at most 3 runs, the others of {}; the plot puts every field on one scale.",
            ctx.repetitions
        ),
        table,
        plot: Plot {
            title: "Mesh fields: error against time".into(),
            x_label: "time (ms)".into(),
            y_label: "mean error".into(),
            series,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_are_the_mean_and_the_largest() {
        assert_eq!(mean_and_largest([1.0, 3.0].into_iter()), (2.0, 3.0));
        assert_eq!(mean_and_largest(std::iter::empty()), (0.0, 0.0));
    }
}
