//! Reading and writing graph files (RON).

use super::{Graph, MAX_TEXT_CHARS, clip};
use crate::fsutil;
use std::fmt;
use std::path::{Path, PathBuf};

/// The graph file format version this build writes for graphs with groups, exposed
/// parameters or parameter presets; a graph without them is written as version
/// [`PLAIN_VERSION`], which older Veneers read.
pub const CURRENT_VERSION: u32 = 2;

/// The version of graphs that use nothing version 2 added.
pub const PLAIN_VERSION: u32 = 1;

/// A graph file that could not be read.
#[derive(Debug)]
pub struct LoadError {
    /// The file, when the graph came from one.
    pub path: Option<PathBuf>,
    /// 1-based line and column, when the error has a position.
    pub position: Option<(usize, usize)>,
    pub message: String,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let path = self
            .path
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or_else(|| "<graph>".into());
        match self.position {
            Some((line, col)) => write!(f, "{path}:{line}:{col}: {}", self.message),
            None => write!(f, "{path}: {}", self.message),
        }
    }
}

impl std::error::Error for LoadError {}

/// Parses a graph from RON text (a leading byte-order mark is skipped). Errors carry the
/// line and column, and quote at most a few lines of the file (a parser message can
/// quote a whole unknown name).
pub fn from_ron(text: &str) -> Result<Graph, LoadError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let options = ron::Options::default().with_recursion_limit(RECURSION_LIMIT);
    let graph: Graph = options.from_str(text).map_err(|err| {
        let message = match err.code {
            ron::Error::ExceededRecursionLimit => {
                format!("values are nested too deeply (more than {RECURSION_LIMIT} levels)")
            }
            code => code.to_string(),
        };
        let (clipped, cut) = clip(&message, 2 * MAX_TEXT_CHARS);
        LoadError {
            path: None,
            position: Some((err.span.start.line, err.span.start.col)),
            message: format!("{clipped}{}", if cut { "…" } else { "" }),
        }
    })?;
    let mut graph = graph;
    super::group::resolve(&mut graph);
    if !(PLAIN_VERSION..=CURRENT_VERSION).contains(&graph.version) {
        let line = text
            .lines()
            .position(|line| line.trim_start().starts_with("version"))
            .map(|l| (l + 1, 5));
        return Err(LoadError {
            path: None,
            position: line,
            message: format!(
                "unsupported graph version {} (this Veneer reads versions {PLAIN_VERSION} to {CURRENT_VERSION})",
                graph.version
            ),
        });
    }
    Ok(graph)
}

/// How deeply values may nest (the RON parser's default), which keeps its recursion
/// well inside the stack.
const RECURSION_LIMIT: usize = 128;

/// Reads a graph file: a regular file of at most [`fsutil::ReadLimit::GRAPH`], in UTF-8;
/// its linked groups take the library's versions (see [`super::library::refresh`]).
pub fn load(path: &Path) -> Result<Graph, LoadError> {
    let failed = |position, message| LoadError {
        path: Some(path.to_path_buf()),
        position,
        message,
    };
    let bytes = fsutil::read_limited(path, fsutil::ReadLimit::GRAPH)
        .map_err(|err| failed(None, format!("cannot read: {err}")))?;
    let text = std::str::from_utf8(&bytes).map_err(|err| {
        let (valid, rest) = bytes.split_at(err.valid_up_to());
        failed(
            Some(end_position(valid)),
            format!("not UTF-8 text: byte 0x{:02X} is not a character", rest[0]),
        )
    })?;
    let mut graph = from_ron(text).map_err(|err| LoadError {
        path: Some(path.to_path_buf()),
        ..err
    })?;
    graph.folder = super::Folder::of_file(path);
    // A linked group whose library file cannot be used keeps the graph's copy: said on
    // stderr, naming the file, whatever command loads the graph.
    for warning in super::library::refresh(&mut graph) {
        use std::io::Write;
        let _ = writeln!(std::io::stderr(), "warning: {}: {warning}", path.display());
    }
    Ok(graph)
}

/// The 1-based line and column just after `valid` (UTF-8 text up to there), counting
/// characters as the RON parser's positions do.
fn end_position(valid: &[u8]) -> (usize, usize) {
    let text = std::str::from_utf8(valid).unwrap_or_default();
    let line_start = text.rfind('\n').map_or(0, |k| k + 1);
    (
        text.matches('\n').count() + 1,
        text[line_start..].chars().count() + 1,
    )
}

/// The canonical RON text of a graph: nodes by id, wires sorted, so the same graph
/// always gives the same bytes.
pub fn to_ron(graph: &Graph) -> String {
    let mut graph = graph.clone();
    graph.canonicalize();
    graph.version = if graph.uses_groups() {
        CURRENT_VERSION
    } else {
        PLAIN_VERSION
    };
    // Groups go last, each written like a graph (a node per line), which one depth
    // limit for the whole file cannot do.
    let groups = std::mem::take(&mut graph.groups);
    let mut text = pretty(&graph, 2);
    if !groups.is_empty() {
        let end = text.rfind(')').unwrap_or(text.len());
        let mut block = String::from("    groups: {\n");
        for (name, definition) in &groups {
            let body = pretty(definition, 2);
            let body = body.trim_end().replace('\n', "\n        ");
            block.push_str(&format!(
                "        {}: {body},\n",
                pretty(name, 0).trim_end()
            ));
        }
        block.push_str("    },\n");
        text.insert_str(end, &block);
    }
    text.push('\n');
    text
}

/// `value` as pretty RON, structures nested past `depth` written on one line.
fn pretty<T: serde::Serialize>(value: &T, depth: usize) -> String {
    let config = ron::ser::PrettyConfig::new()
        .depth_limit(depth)
        .indentor("    ")
        .struct_names(false);
    ron::ser::to_string_pretty(value, config).expect("graphs always serialise")
}

/// Writes a graph atomically (temporary file, then rename).
pub fn save(graph: &Graph, path: &Path) -> std::io::Result<()> {
    fsutil::write_atomic(path, to_ron(graph).as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::{Frame, NodeKind};

    #[test]
    fn frames_round_trip_and_are_left_out_when_there_are_none() {
        let mut graph = Graph::default();
        graph.add("material", NodeKind::Material);
        assert!(!to_ron(&graph).contains("frames"));
        graph.frames.push(Frame {
            title: "grain".into(),
            min: (-10.0, -50.0),
            max: (400.0, 300.0),
            color: (0.4, 0.6, 0.9),
        });
        let text = to_ron(&graph);
        assert_eq!(from_ron(&text).unwrap(), graph);
        assert_eq!(to_ron(&from_ron(&text).unwrap()), text);
    }

    #[test]
    fn the_alpha_mask_reads_as_files_write_it_and_as_design_first_gave_it() {
        let graph = |alpha: &str| {
            let text = format!("(version: 1, nodes: [(id: 1, kind: Material)], alpha: {alpha})");
            from_ron(&text).map(|graph| graph.alpha)
        };
        let mask = crate::graph::AlphaMode::Mask { cutoff: 0.3 };
        assert_eq!(graph("Mask(cutoff: 0.3)").unwrap(), mask);
        assert_eq!(graph("Mask((cutoff: 0.3))").unwrap(), mask);
        assert_eq!(graph("Blend").unwrap(), crate::graph::AlphaMode::Blend);
        assert_eq!(graph("Opaque").unwrap(), crate::graph::AlphaMode::Opaque);
        for bad in ["Mask", "Mask(0.3)", "Mask((cut: 0.3))", "Clip"] {
            assert!(graph(bad).is_err(), "{bad}");
        }
        // Written in the one form, which reads back.
        let mut written = Graph::default();
        written.add("material", NodeKind::Material);
        written.alpha = mask;
        let text = to_ron(&written);
        assert!(
            text.contains("alpha: Mask(") && !text.contains("Mask(("),
            "{text}"
        );
        assert_eq!(from_ron(&text).unwrap().alpha, mask);
    }
}
