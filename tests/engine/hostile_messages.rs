//! Messages that must name the real cause and must not act on the user's terminal:
//! control characters taken from a file (a label, a glTF URI) are printed escaped, a
//! special file given as a mesh is called what it is, and a glTF accessor that reads
//! past its buffer is said to, not taken for a mesh without triangles.

use crate::support::{root, run_veneer, temp_dir};

/// An OSC sequence that retitles a terminal, a screen clear, a bell and a C1 CSI.
const ESCAPES: &str = "\u{1b}]0;pwned\u{7}\u{1b}[2J\u{9b}31m";

/// Asserts that `bytes` carry no control character but line breaks and tabs.
fn assert_no_controls(what: &str, bytes: &[u8]) {
    let text = String::from_utf8_lossy(bytes);
    let control = text
        .chars()
        .find(|&c| c.is_control() && c != '\n' && c != '\t');
    assert_eq!(
        control, None,
        "{what} carries a raw control character: {text:?}"
    );
}

#[test]
fn control_characters_from_a_graph_reach_the_terminal_escaped() {
    let dir = temp_dir("escaped-label");
    let text = std::fs::read_to_string(root("tests/bad/unknown_pin.ron")).expect("bad graph");
    let graph = dir.join("label.ron");
    let label = format!("grain{ESCAPES}");
    std::fs::write(&graph, text.replace("\"grain\"", &format!("{label:?}"))).expect("written");
    let output = run_veneer(&["check", graph.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(1));
    assert_no_controls("stderr", &output.stderr);
    assert_no_controls("stdout", &output.stdout);
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains("grain\\u{1b}]0;pwned\\u{7}"),
        "the label is not shown escaped: {message}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn control_characters_in_a_gltf_uri_reach_the_terminal_escaped() {
    let dir = temp_dir("escaped-uri");
    let text = std::fs::read_to_string(root("tests/meshes/tetrahedron.gltf")).expect("glTF");
    let start = text.find("data:application").expect("an embedded buffer");
    let end = start + text[start..].find('"').expect("the URI's end");
    let uri = serde_json::to_string(&format!("missing{ESCAPES}.bin")).unwrap();
    let mesh = dir.join("uri.gltf");
    let edited = format!("{}{}{}", &text[..start - 1], uri, &text[end + 1..]);
    std::fs::write(&mesh, edited).expect("written");
    let output = run_veneer(&["mesh", mesh.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(1), "{output:?}");
    assert_no_controls("stderr", &output.stderr);
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("\\u{1b}"), "{message}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_special_file_given_as_a_mesh_is_called_what_it_is() {
    let output = run_veneer(&["mesh", "/dev/zero"]);
    assert_eq!(output.status.code(), Some(1));
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(message.contains("character device"), "{message}");
    assert!(!message.contains("unknown mesh"), "{message}");
}

#[test]
fn a_gltf_accessor_past_its_buffer_is_named_not_taken_for_an_empty_mesh() {
    let dir = temp_dir("accessor-offset");
    let text = std::fs::read_to_string(root("tests/meshes/tetrahedron.gltf")).expect("glTF");
    let mut json: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    for (accessor, what) in [(0, "POSITION"), (1, "indices")] {
        let mut edited = json.clone();
        edited["accessors"][accessor]["byteOffset"] = serde_json::json!(4_294_967_292u64);
        let mesh = dir.join(format!("offset{accessor}.gltf"));
        std::fs::write(&mesh, edited.to_string()).expect("written");
        let output = run_veneer(&["mesh", mesh.to_str().unwrap()]);
        let message = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{message}");
        assert!(
            message.contains(&format!("the {what} accessor ({accessor})"))
                && message.contains("past the end of buffer view"),
            "{message}"
        );
        assert!(!message.contains("no triangles"), "{message}");
    }
    // A buffer view past the end of its buffer.
    json["bufferViews"][1]["byteOffset"] = serde_json::json!(64);
    let mesh = dir.join("view.gltf");
    std::fs::write(&mesh, json.to_string()).expect("written");
    let output = run_veneer(&["mesh", mesh.to_str().unwrap()]);
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("past the end of buffer 0 (72 bytes)"),
        "{message}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
