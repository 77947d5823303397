//! `veneer report --quick` writes every section: Markdown, a CSV per table, a PNG plot.

use crate::support::{temp_dir, veneer};

#[test]
fn a_quick_report_writes_every_section_with_its_table_and_plot() {
    let dir = temp_dir("report");
    let output = veneer()
        .args(["report", "--quick", "--repetitions", "1", "-o"])
        .arg(&dir)
        .output()
        .expect("veneer runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let markdown = std::fs::read_to_string(dir.join("report.md")).expect("report.md");
    for section in ["precision", "hashes", "octaves", "geodesics", "detail"] {
        assert!(
            markdown.contains(&format!("({section}.png)")),
            "{section} plot linked"
        );
        let csv = std::fs::read_to_string(dir.join(format!("{section}.csv"))).expect("csv");
        assert!(csv.lines().count() > 2, "{section}: a header and rows");
        let plot = image::open(dir.join(format!("{section}.png"))).expect("the plot decodes");
        assert_eq!((plot.width(), plot.height()), (800, 500));
    }
    let adapter = crate::support::gpu().adapter_description();
    assert!(
        markdown.contains(&adapter),
        "the adapter is stated: {adapter}"
    );
    let bad = veneer()
        .args(["report", "--repetitions", "0"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(1));
}
