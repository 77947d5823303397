//! `veneer report --quick` writes every section: Markdown, a CSV per table, a PNG plot;
//! the thesis's tables hold finite, positive figures; the progress bar counts its steps.

use crate::support::{temp_dir, veneer};
use std::cell::Cell;

/// The rows of a CSV the report wrote (no cell of these tables holds a comma), header
/// first.
fn rows(csv: &str) -> Vec<Vec<String>> {
    csv.lines()
        .map(|line| line.split(',').map(String::from).collect())
        .collect()
}

/// The cell as a finite number (a share in percent as its fraction).
fn finite(cell: &str) -> f64 {
    let value: f64 = match cell.strip_suffix('%') {
        Some(percent) => percent.parse::<f64>().map(|p| p / 100.0),
        None => cell.parse(),
    }
    .unwrap_or_else(|_| panic!("{cell:?} is a number"));
    assert!(value.is_finite(), "{cell:?} is finite");
    value
}

#[test]
fn a_quick_report_writes_every_section_and_the_thesis_tables_hold_finite_figures() {
    let dir = temp_dir("report");
    let gpu = crate::support::gpu();
    let settings = veneer::report::Settings {
        repetitions: 2,
        quick: true,
    };
    let steps = Cell::new(0);
    veneer::report::write(gpu, &settings, &dir, &|| steps.set(steps.get() + 1))
        .expect("the report is written");
    assert_eq!(
        steps.get(),
        veneer::report::steps(&settings),
        "the progress bar's length"
    );
    let markdown = std::fs::read_to_string(dir.join("report.md")).expect("report.md");
    for section in [
        "precision",
        "hashes",
        "octaves",
        "geodesics",
        "detail",
        "distance_times",
        "frame_rates",
        "mesh_fields",
        "fitting",
    ] {
        assert!(
            markdown.contains(&format!("({section}.png)")),
            "{section} plot linked"
        );
        let csv = std::fs::read_to_string(dir.join(format!("{section}.csv"))).expect("csv");
        assert!(csv.lines().count() > 2, "{section}: a header and rows");
        let plot = image::open(dir.join(format!("{section}.png"))).expect("the plot decodes");
        assert_eq!((plot.width(), plot.height()), (800, 500));
    }
    let adapter = gpu.adapter_description();
    assert!(
        markdown.contains(&adapter),
        "the adapter is stated: {adapter}"
    );
    assert!(markdown.contains("GeForce 8600 GT"), "the thesis's GPU");

    let read = |name: &str| rows(&std::fs::read_to_string(dir.join(name)).expect(name));

    // Fitting: Adam from one start and from three (with and without the global search)
    // and random search, each with finite figures; the fit ends below the start.
    let fitting = read("fitting.csv");
    let methods: Vec<&str> = fitting[1..].iter().map(|row| row[1].as_str()).collect();
    assert_eq!(methods.len(), 4, "{fitting:?}");
    assert!(methods[2].ends_with("with global search"), "{methods:?}");
    assert!(methods[3].starts_with("random search ("), "{methods:?}");
    for row in &fitting[1..] {
        let (seconds, left, error) = (finite(&row[2]), finite(&row[3]), finite(&row[4]));
        assert!(seconds > 0.0 && (0.0..=1.0).contains(&error), "{row:?}");
        assert!(left < 1.0 || row[1].starts_with("random"), "{row:?}");
    }

    // Mesh fields: more rays, less occlusion error; curvatures near their analytic values.
    let fields = read("mesh_fields.csv");
    let error = |field: &str, setting: &str| {
        let row = fields
            .iter()
            .find(|row| row[0] == field && row[2].starts_with(setting))
            .unwrap_or_else(|| panic!("{field}, {setting}: {fields:?}"));
        finite(&row[3])
    };
    assert!(error("ambient occlusion", "4 rays") > error("ambient occlusion", "256 rays"));
    assert!(error("mean curvature", "against") < 0.01);
    assert!(error("thickness", "64 rays") < 0.05);

    // Table 5.1: a row per model, the mean and deviation of every method.
    let times = read("distance_times.csv");
    assert_eq!(
        times[0][..3],
        ["mesh", "thesis model of similar size", "triangles"]
    );
    assert_eq!(times.len(), 1 + 4, "four models");
    for row in &times[1..] {
        assert!(finite(&row[2]) >= 500.0, "{row:?}: triangles");
        for pair in row[3..].chunks(2) {
            assert!(finite(&pair[0]) > 0.0, "{row:?}: a mean time");
            assert!(finite(&pair[1]) >= 0.0, "{row:?}: a deviation");
        }
        assert_eq!(row.len(), 3 + 2 * 4, "exact, heat, robust heat, Dijkstra");
    }

    // Tables 5.2 and 5.3: near and far frames a second of every texture on each model.
    let frames = read("frame_rates.csv");
    let header = &frames[0];
    for texture in [
        "Water/Sand",
        "Moss",
        "Rust",
        "Water/Lava",
        "Isolines",
        "Waves",
    ] {
        for view in ["near", "far"] {
            let column = format!("{texture} {view} fps");
            assert!(header.contains(&column), "{column} in {header:?}");
        }
    }
    assert_eq!(frames.len(), 1 + 4, "four models");
    for row in &frames[1..] {
        let (near, far) = (finite(&row[2]), finite(&row[3]));
        assert!(
            near > 0.3 && far > 0.0 && near > 4.0 * far && near <= 1.0,
            "{row:?}: near, the mesh fills most of the frame; far, a little of it"
        );
        for fps in &row[4..row.len() - 1] {
            assert!(finite(fps) > 0.0, "{row:?}: frames a second");
        }
        assert!(
            ["GPU timestamps", "wall clock"].contains(&row[row.len() - 1].as_str()),
            "{row:?}: how it was timed"
        );
    }

    let bad = veneer()
        .args(["report", "--repetitions", "0"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(1));
}
