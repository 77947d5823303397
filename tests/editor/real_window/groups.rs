//! Inside a group: its nodes show their thumbnails (as they work in the group's first
//! instance), and a numerical hazard inside it marks the group node outside.

use super::canvas::{canvas_area, islands};
use super::session::{STEP, Session, require_tools};
use super::shot::{Rect, Shot};
use crate::support::wood_with_a_hazard_inside;

/// The warning sign's colour (`canvas/viewer.rs`).
const WARNING: [u8; 3] = [230, 180, 60];

/// Pixels of `area` that are near white: thumbnails (several of the group's are white
/// squares of 64 × 64); titles and values, thin strokes, make a few hundred.
fn bright_pixels(shot: &Shot, area: Rect) -> usize {
    count(shot, area, |p| p.iter().all(|&c| c > 240))
}

/// Pixels of `area` near the warning sign's colour.
fn warning_pixels(shot: &Shot, area: Rect) -> usize {
    count(shot, area, |p| {
        (0..3).all(|c| p[c].abs_diff(WARNING[c]) <= 25)
    })
}

fn count(shot: &Shot, area: Rect, keep: impl Fn([u8; 3]) -> bool) -> usize {
    let area = area.clip(shot);
    let pixels = (area.y0..area.y1).flat_map(|y| (area.x0..area.x1).map(move |x| (x, y)));
    pixels.filter(|&(x, y)| keep(shot.px(x, y))).count()
}

/// The group node's title bar (the wood node and the material are joined by their
/// wire into one island: the group node is its left part, at its top).
fn title_bar(shot: &Shot) -> Option<Rect> {
    let island = islands(shot, canvas_area(shot))
        .into_iter()
        .max_by_key(|r| (r.x1 - r.x0) * (r.y1 - r.y0))?;
    Some(Rect {
        x1: island.x0 + (island.x1 - island.x0) * 2 / 5,
        y1: island.y0 + 36,
        ..island
    })
}

#[test]
fn inside_a_group_nodes_show_thumbnails_and_a_hazard_marks_the_group_in_a_real_window() {
    require_tools();
    let mut session = Session::start("group_thumbnails");
    let file = session.dir.join("wood.ron");
    veneer::graph::save(&wood_with_a_hazard_inside(), &file).expect("the graph is written");
    session.step("open wood with a hazard inside its group");
    session.start_editor(&file, "wood.ron — Veneer");
    for _ in 1..=2 {
        session.step("the group node's title bar shows the warning sign");
        let bar = session.wait_for("the warning sign on the group node", STEP, |s| {
            let shot = s.shot();
            let bar = title_bar(&shot)?;
            (warning_pixels(&shot, bar) >= 6).then_some(bar)
        });

        session.step("Tab into the group: its nodes show their thumbnails");
        session.click((bar.x0 + 30, bar.y0 + 10), "1");
        // The click selects the group before Tab asks for it: on a loaded machine the
        // two can otherwise reach the editor in one frame, whose shortcuts run before
        // the canvas sees the click (Tab with nothing selected opens the search).
        let canvas = canvas_area(&session.shot());
        session.settled(canvas);
        session.key("Tab");
        // (About 9,000 with the thumbnails; the titles and values alone a few hundred.)
        session.wait_for("the group's nodes with their thumbnails", STEP, |s| {
            let shot = s.shot();
            (bright_pixels(&shot, canvas_area(&shot)) > 4_000).then_some(())
        });

        session.step("a click on empty canvas (its bottom left corner), Tab: back up");
        let canvas = canvas_area(&session.shot());
        session.click((canvas.x0 + 12, canvas.y1 - 12), "1");
        session.key("Tab");
    }
    session.finish();
}
