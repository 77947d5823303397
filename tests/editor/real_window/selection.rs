//! One selection, as in Blender: a click selects the clicked node alone (whatever a
//! rectangle selected before), and Delete or X deletes what is selected.

use super::canvas::{grid, id, labels};
use super::session::{Session, require_tools};
use veneer::graph::NodeKind;

#[test]
fn a_click_after_a_rectangle_selects_one_node_and_delete_or_x_deletes_it_in_a_real_window() {
    require_tools();
    let mut session = Session::start("click_after_rectangle");
    let kinds = [
        NodeKind::Position,
        NodeKind::Uv,
        NodeKind::Time,
        NodeKind::Invert,
        NodeKind::Gamma,
        NodeKind::Remap,
    ];
    let mut graph = grid(3, &kinds);
    session.step("open six nodes in two rows of three");
    let (file, mut drawn) = session.open_drawn("grid.ron", &graph);
    // Each row: a rectangle around its first two nodes, a click on the third, a key.
    for (row, key) in [(0, "Delete"), (1, "x")] {
        let label = |column: usize| format!("n{}", 3 * row + column);
        let first = drawn.rect(id(&graph, &label(0)));
        let second = drawn.rect(id(&graph, &label(1)));
        session.step(&format!(
            "draw a rectangle around {} and {} from empty canvas",
            label(0),
            label(1)
        ));
        session.drag(
            (second.x1 + 20, second.y1.max(first.y1) + 20),
            (first.x0 - 10, first.y0 - 10),
            None,
        );
        session.step(&format!("click {}'s title", label(2)));
        session.click(drawn.title(id(&graph, &label(2))), "1");
        session.step(&format!("press {key}"));
        session.key(key);
        session.expect_edited(&format!(
            "pressing {key} with {} selected (clicked after a rectangle around {} and {}) \
             deleted nothing: {key} must delete the selection",
            label(2),
            label(0),
            label(1)
        ));
        session.step("save with Ctrl+S");
        let saved = session.save(&file);
        graph.nodes.retain(|node| node.label != label(2));
        if labels(&saved) != labels(&graph) {
            session.fail(&format!(
                "after a rectangle around {} and {}, a click on {} and {key}, the saved graph \
                 has {:?}, not {:?}: the click must select {} alone (as in Blender), and {key} \
                 delete only it",
                label(0),
                label(1),
                label(2),
                labels(&saved),
                labels(&graph),
                label(2)
            ));
        }
        drawn = session.drawn(&graph);
    }
    session.close_editor();
    session.finish();
}
