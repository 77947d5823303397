//! What a user does in the first minute, and files that must change nothing.

use super::session::{STEP, Session, require_tools, root};
use super::shot::{Rect, diff, free_spots, full, hint_pixels};
use std::process::Command;

#[test]
fn add_wire_save_and_reopen_in_a_real_window() {
    require_tools();
    let mut session = Session::start("add_wire_save_reopen");
    let dir = session.dir.clone();
    let original =
        veneer::graph::load(&root("graphs/marble.ron")).expect("the marble preset loads");
    let copy = dir.join("marble copy.ron");
    std::fs::copy(root("graphs/marble.ron"), &copy).expect("copy the preset");
    let copy_bytes = std::fs::read(&copy).unwrap();

    session.step("start the editor on a copy of the marble preset");
    session.start_editor(&copy, "marble copy.ron — Veneer");
    let whole = full(&session.shot());
    session.settled(whole);

    // The graph opens framed, filling the canvas: zoom out about its top-left corner.
    session.step("make room: the wheel zooms out about the pointer");
    let first = session.zoom_out((12, 40), 2);

    session.step("find empty canvas for two nodes");
    let (at_noise, at_remap) = match free_spots(&first) {
        Some(spots) => spots,
        None => session.fail("no empty canvas of 420 × 280 pixels for each of two nodes"),
    };

    session.step("add a Noise node: Space at the mouse, type 'noise', Enter");
    let noise = session.add_node(at_noise, "noise");
    session.step("add a Remap node: Space at the mouse, type 'remap', Enter");
    let remap = session.add_node(at_remap, "remap");
    session.expect_title("* marble copy.ron — Veneer");

    session.step("wire Noise's output to Remap's first input by dragging");
    let from = match noise.output {
        Some(pin) => pin,
        None => session.fail("the new Noise node shows no output pin at its right edge"),
    };
    let to = match remap.input {
        Some(pin) => pin,
        None => session.fail("the new Remap node shows no input pin at its left edge"),
    };
    let before = session.shot();
    let hints = hint_pixels(&before, remap.bounds);
    session.drag_wire(from, to, noise.bounds);
    // A wire is drawn symmetric about its middle, and once connected Remap's input no
    // longer asks (in orange) to be connected.
    let middle = Rect::around(((from.0 + to.0) / 2, (from.1 + to.1) / 2), 4);
    session.wait_for(
        "the wire connected and Remap's 'connect' hint gone",
        STEP,
        |s| {
            let now = s.shot();
            let wire = diff(&before, &now, middle, false).0 > 0;
            (wire && (hints == 0 || hint_pixels(&now, remap.bounds) == 0)).then_some(())
        },
    );

    session.step("save with Ctrl+S");
    session.key("ctrl+s");
    session.wait_for("the file saved with 2 more nodes", STEP, |_| {
        veneer::graph::load(&copy)
            .ok()
            .filter(|graph| graph.nodes.len() == original.nodes.len() + 2)
    });
    session.expect_title("marble copy.ron — Veneer");

    session.step("save as with Ctrl+Shift+S, a typed path and Enter");
    let saved_as = dir.join("saved as.ron");
    let before = session.shot();
    session.key("ctrl+shift+s");
    session.expect_dialog(&before, "the Save as dialog");
    session.type_text(&saved_as.display().to_string());
    session.key("Return");
    session.wait_for("the file written by Save as", STEP, |_| {
        veneer::graph::load(&saved_as).ok()
    });
    session.expect_title("saved as.ron — Veneer");

    session.step("close the editor (SIGTERM, as a desktop's logout or `kill` does)");
    session.close_editor();
    let state = dir.join("state/veneer");
    let leftovers: Vec<String> = std::fs::read_dir(&state)
        .map(|entries| {
            entries
                .flatten()
                .map(|entry| entry.file_name().to_string_lossy().into_owned())
                .filter(|name| name.starts_with("recovery"))
                .collect()
        })
        .unwrap_or_default();
    if !leftovers.is_empty() {
        session.fail(&format!(
            "the saved session left work to recover in {}: {leftovers:?}",
            state.display()
        ));
    }

    session.step("reopen the saved file");
    let saved_bytes = std::fs::read(&saved_as).unwrap();
    session.start_editor(&saved_as, "saved as.ron — Veneer");
    session.settled(whole);
    session.close_editor();
    if std::fs::read(&saved_as).unwrap() != saved_bytes {
        session.fail("opening and closing the saved file changed it");
    }

    session.step("compare the saved files with the edits");
    let saved = veneer::graph::load(&copy).expect("the Ctrl+S file loads");
    let again = veneer::graph::load(&saved_as).expect("the Save as file loads");
    if saved != again {
        session.fail("Ctrl+S and Save as wrote different graphs");
    }
    if std::fs::read(&copy).unwrap() == copy_bytes {
        session.fail("Ctrl+S did not change the file");
    }
    let added: Vec<_> = saved
        .nodes
        .iter()
        .filter(|node| original.node(node.id).is_none())
        .collect();
    let kinds: Vec<&str> = added.iter().map(|node| node.kind.title()).collect();
    let (Some(noise_node), Some(remap_node)) = (
        added.iter().find(|node| node.kind.title() == "Noise"),
        added.iter().find(|node| node.kind.title() == "Remap"),
    ) else {
        session.fail(&format!(
            "the saved file's new nodes are {kinds:?}, not a Noise and a Remap"
        ))
    };
    if added.len() != 2 {
        session.fail(&format!(
            "the saved file has {} new nodes: {kinds:?}",
            added.len()
        ));
    }
    for node in &original.nodes {
        let kept = saved.node(node.id).is_some_and(|saved| {
            saved.kind == node.kind && saved.inputs == node.inputs && saved.label == node.label
        });
        if !kept {
            session.fail(&format!(
                "the preset's node {} changed in the saved file",
                node.id
            ));
        }
    }
    let output = noise_node.kind.signature().outputs[0].name;
    let input = remap_node.kind.signature().inputs[0].name;
    let wire = veneer::graph::Wire {
        from: veneer::graph::PinRef::new(noise_node.id, output),
        to: veneer::graph::PinRef::new(remap_node.id, input),
    };
    let new_wires: Vec<_> = saved
        .wires
        .iter()
        .filter(|wire| !original.wires.contains(wire))
        .collect();
    if new_wires != [&wire] || saved.wires.len() != original.wires.len() + 1 {
        session.fail(&format!(
            "the saved file's new wires are {new_wires:?}, not only {wire:?} \
             (and {} of the preset's {} wires kept)",
            saved
                .wires
                .iter()
                .filter(|w| original.wires.contains(w))
                .count(),
            original.wires.len()
        ));
    }
    session.finish();
}

/// A chain of `count` nodes — a position, transforms, a material — every one of them
/// at the origin, as a generator that writes no positions leaves them.
fn stacked_chain(count: usize) -> veneer::graph::Graph {
    use veneer::graph::{Graph, NodeKind, PinRef, Wire};
    let mut graph = Graph::default();
    let mut previous = (graph.add("p", NodeKind::Position), "position");
    for k in 1..count - 1 {
        let next = graph.add(&format!("t{k}"), NodeKind::Transform);
        graph.wires.push(Wire {
            from: PinRef::new(previous.0, previous.1),
            to: PinRef::new(next, "p"),
        });
        previous = (next, "p");
    }
    let material = graph.add("material", NodeKind::Material);
    graph.wires.push(Wire {
        from: PinRef::new(previous.0, previous.1),
        to: PinRef::new(material, "normal"),
    });
    graph
}

#[test]
fn ten_thousand_nodes_at_one_point_open_laid_out_in_a_real_window() {
    require_tools();
    let mut session = Session::start("stacked_nodes");
    let path = session.dir.join("stacked.ron");
    let graph = stacked_chain(10_000);
    veneer::graph::save(&graph, &path).expect("the graph saves");

    session.step("open 10,000 nodes at one point: they are laid out, the document edited");
    session.start_editor(&path, "* stacked.ron — Veneer");
    let whole = full(&session.shot());
    session.settled(whole);

    session.step("save with Ctrl+S: the layout is kept, nothing else changed");
    session.key("ctrl+s");
    let saved = session.wait_for("the file saved with its nodes apart", STEP, |_| {
        veneer::graph::load(&path).ok().filter(|saved| {
            let mut positions: Vec<_> = saved.nodes.iter().map(|n| n.position).collect();
            positions.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
            positions.dedup();
            positions.len() == saved.nodes.len()
        })
    });
    session.expect_title("stacked.ron — Veneer");
    if saved.wires != graph.wires || saved.nodes.len() != graph.nodes.len() {
        session.fail("saving the laid-out graph changed more than its positions");
    }
    session.close_editor();
    session.finish();
}

#[test]
fn a_fifo_for_a_recent_list_and_a_group_containing_itself_change_nothing_in_a_real_window() {
    require_tools();
    let mut session = Session::start("fifo_and_group_loop");
    // A FIFO where the recent-files list goes: opening a file remembers it there, which
    // waited for a reader forever (a black window that ignored SIGTERM).
    let state = session.dir.join("state/veneer");
    std::fs::create_dir_all(&state).expect("the state folder");
    let status = Command::new("mkfifo")
        .arg(state.join("recent.ron"))
        .status()
        .expect("mkfifo");
    assert!(status.success());
    let path = session.dir.join("loop.ron");
    std::fs::write(&path, crate::groups::SELF_CONTAINING).expect("the graph is written");

    session.step("open a graph whose group contains itself: it opens, not edited");
    session.start_editor(&path, "loop.ron — Veneer");
    let whole = full(&session.shot());
    session.settled(whole);
    session.expect_title("loop.ron — Veneer");

    session.step("close the editor with SIGTERM: it ends, the file as it was");
    session.close_editor();
    if std::fs::read_to_string(&path).unwrap() != crate::groups::SELF_CONTAINING {
        session.fail("the graph file changed");
    }
    session.finish();
}
