//! The side panel keeps its width: clicking a number field of the preview's lighting
//! row (which turns it into a text box) does not widen the panel over the graph.

use super::canvas::{canvas_area, grid};
use super::session::{Session, require_tools};
use super::shot::{Rect, Shot, full};
use veneer::graph::{NodeKind, Shading};

/// The fill of an idle button, menu or number field (egui's dark theme).
const WIDGET: [u8; 3] = [60, 60, 60];

/// The number fields of the lighting row, after its environment menu.
const FIELDS: [&str; 3] = ["turn", "key light", "exposure"];

/// Where the side panel begins: the column right of the canvas.
fn panel_edge(shot: &Shot) -> i32 {
    canvas_area(shot).x1
}

/// The filled boxes of [`WIDGET`] colour in `area` (buttons, menus, fields), found
/// from their top rows: a run of the colour at least 20 pixels long with none above
/// it, followed down its left edge (inside the rounded corner) as far as the colour
/// goes. Text within a box leaves its top row and left edge alone.
fn widgets(shot: &Shot, area: Rect) -> Vec<Rect> {
    let area = area.clip(shot);
    let fill = |x: i32, y: i32| area.contains((x, y)) && shot.px(x, y) == WIDGET;
    let mut found = Vec::new();
    for y in area.y0..area.y1 {
        let mut x = area.x0;
        while x < area.x1 {
            let start = x;
            while fill(x, y) {
                x += 1;
            }
            let middle = (start + x) / 2;
            if x - start >= 20 && !fill(middle, y - 1) {
                // Down its left edge while the box has a border of another colour
                // beside it (not into a wider box right below).
                let mut bottom = y;
                while fill(start + 1, bottom) && !fill(start - 3, bottom) {
                    bottom += 1;
                }
                found.push(Rect {
                    x0: start,
                    y0: y,
                    x1: x,
                    y1: bottom,
                });
            }
            x += 1;
        }
    }
    found
}

/// The lighting's number fields ([`FIELDS`]), however its rows wrap: the buttons, menus
/// and fields of the side panel after the shading row (the row whose first widget, the
/// "metallic-roughness" menu, is the widest first widget of any row), in reading order,
/// are the environment menu, then the fields.
fn lighting_fields(shot: &Shot) -> Option<Vec<Rect>> {
    let panel = Rect {
        x0: panel_edge(shot) + 4,
        ..full(shot)
    };
    let mut rows: Vec<Vec<Rect>> = Vec::new();
    for widget in widgets(shot, panel) {
        if !(12..=30).contains(&(widget.y1 - widget.y0)) {
            continue;
        }
        match rows
            .iter_mut()
            .find(|row| (widget.y0 - row[0].y0).abs() <= 4)
        {
            Some(row) => row.push(widget),
            None => rows.push(vec![widget]),
        }
    }
    rows.sort_by_key(|row| row[0].y0);
    for row in &mut rows {
        row.sort_by_key(|r| r.x0);
    }
    let shading = (0..rows.len()).max_by_key(|&i| rows[i][0].x1 - rows[i][0].x0)?;
    let after: Vec<Rect> = rows[shading + 1..].iter().flatten().copied().collect();
    (after.len() > FIELDS.len()).then(|| after[1..=FIELDS.len()].to_vec())
}

#[test]
fn clicking_the_lighting_fields_keeps_the_side_panel_width_in_a_real_window() {
    require_tools();
    let mut session = Session::start("lighting_fields_panel_width");
    let mut graph = grid(1, &[NodeKind::Position]);
    graph.shading = Shading::MetallicRoughness;
    session.step("open a metallic-roughness graph: the preview's lighting row shows");
    session.open_drawn("lit.ron", &graph);
    let whole = full(&session.shot());
    let opened = session.settled(whole);
    let edge = panel_edge(&opened);
    // Found once: while the panel keeps its width, the fields stay where they are.
    let Some(fields) = lighting_fields(&opened) else {
        session.fail(
            "cannot find the preview's lighting rows (environment, turn, key light; exposure, \
             tone map, backdrop) in the side panel",
        );
    };
    for round in 1..=2 {
        for (name, field) in FIELDS.iter().zip(&fields) {
            session.step(&format!(
                "click the {name} field, then Escape ({round} of 2)"
            ));
            session.click(((field.x0 + field.x1) / 2, (field.y0 + field.y1) / 2), "1");
            let clicked = session.settled(whole);
            session.key("Escape");
            let left = session.settled(whole);
            for (when, now) in [("once clicked", &clicked), ("after Escape", &left)] {
                let moved = panel_edge(now);
                if moved != edge {
                    session.fail(&format!(
                        "clicking the {name} field of the preview's lighting row moved the side \
                         panel's left edge from x = {edge} to x = {moved} {when} ({} px wider): \
                         the panel must keep its width, not cover the graph",
                        edge - moved
                    ));
                }
            }
        }
    }
    session.close_editor();
    session.finish();
}
