//! The group library: node groups saved one RON file each, reused in any graph. Veneer
//! ships the groups of `graphs/lib/` inside the binary; an artist's own go to the user
//! library folder (`$VENEER_LIBRARY`, else `$XDG_DATA_HOME/veneer/library`, else
//! `~/.local/share/veneer/library`), where a group of the same name takes precedence.
//!
//! A graph keeps a copy of every group it uses. A copy marked `linked` follows the
//! library: loading the graph takes the library's current version, so editing a
//! library group updates every graph that uses it; *Make local* clears the mark.

use super::group::{GroupDef, resolve};
use super::{Graph, LoadError, MAX_TEXT_CHARS, clip};
use crate::fsutil;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The library format version this build writes and reads.
pub const LIBRARY_VERSION: u32 = 1;

/// A library file: one group and its name.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LibraryGroup {
    pub version: u32,
    pub name: String,
    pub group: GroupDef,
}

/// The groups shipped in the binary: file stem and RON text.
pub const SHIPPED: [(&str, &str); 2] = [
    ("ring_wood", include_str!("../../graphs/lib/ring_wood.ron")),
    (
        "veined_marble",
        include_str!("../../graphs/lib/veined_marble.ron"),
    ),
];

/// Where a library group comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// Shipped with Veneer (`graphs/lib/`).
    Shipped,
    /// The user library folder.
    User(PathBuf),
}

/// Parses a library file.
pub fn from_ron(text: &str) -> Result<LibraryGroup, LoadError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let group: LibraryGroup = ron::from_str(text).map_err(|err| {
        let message = err.code.to_string();
        LoadError {
            path: None,
            position: Some((err.span.start.line, err.span.start.col)),
            message: clip(&message, 2 * MAX_TEXT_CHARS).0.to_string(),
        }
    })?;
    if group.version != LIBRARY_VERSION {
        return Err(LoadError {
            path: None,
            position: None,
            message: format!(
                "unsupported library version {} (this Veneer reads version {LIBRARY_VERSION})",
                group.version
            ),
        });
    }
    Ok(group)
}

/// The canonical text of a library file.
pub fn to_ron(name: &str, group: &GroupDef) -> String {
    let mut group = group.clone();
    group.canonicalize();
    group.linked = false;
    let file = LibraryGroup {
        version: LIBRARY_VERSION,
        name: name.to_string(),
        group,
    };
    let config = ron::ser::PrettyConfig::new()
        .depth_limit(3)
        .indentor("    ")
        .struct_names(false);
    let mut text = ron::ser::to_string_pretty(&file, config).expect("groups always serialise");
    text.push('\n');
    text
}

/// The user library folder.
pub fn user_folder() -> Option<PathBuf> {
    let variable = |name: &str| std::env::var_os(name).filter(|value| !value.is_empty());
    if let Some(folder) = variable("VENEER_LIBRARY") {
        return Some(PathBuf::from(folder));
    }
    if let Some(data) = variable("XDG_DATA_HOME") {
        return Some(PathBuf::from(data).join("veneer/library"));
    }
    variable("HOME").map(|home| PathBuf::from(home).join(".local/share/veneer/library"))
}

/// Reads library file `path`.
pub fn load(path: &Path) -> Result<LibraryGroup, LoadError> {
    let failed = |message: String| LoadError {
        path: Some(path.to_path_buf()),
        position: None,
        message,
    };
    let bytes = fsutil::read_limited(path, fsutil::ReadLimit::GRAPH)
        .map_err(|error| failed(format!("cannot read: {error}")))?;
    let text = String::from_utf8(bytes).map_err(|_| failed("not UTF-8 text".into()))?;
    from_ron(&text).map_err(|error| LoadError {
        path: Some(path.to_path_buf()),
        ..error
    })
}

/// The library group called `name` (in canonical order): the user's if there is one,
/// else the shipped one. A user file of that name that cannot be used is an error
/// naming it (and why), never passed over in silence; so is a name that cannot name a
/// file (see [`super::names`]).
pub fn find(name: &str) -> Result<Option<(GroupDef, Source)>, LoadError> {
    let found = find_as_written(name)?;
    Ok(found.map(|(mut group, source)| {
        group.canonicalize();
        (group, source)
    }))
}

/// [`find`], the group as its file has it.
fn find_as_written(name: &str) -> Result<Option<(GroupDef, Source)>, LoadError> {
    super::names::file_name_part("group", name).map_err(|message| LoadError {
        path: None,
        position: None,
        message: format!("{message}; the library is not searched for it"),
    })?;
    if let Some(folder) = user_folder() {
        let path = folder.join(format!("{name}.ron"));
        if std::fs::symlink_metadata(&path).is_ok() {
            let group = load(&path)?;
            if group.name != name {
                return Err(LoadError {
                    path: Some(path),
                    position: None,
                    message: format!(
                        "holds group '{}', not '{}': a library file is named after its group",
                        super::names::shown(&group.name),
                        super::names::shown(name)
                    ),
                });
            }
            return Ok(Some((group.group, Source::User(path))));
        }
    }
    Ok(SHIPPED
        .iter()
        .find(|(stem, _)| *stem == name)
        .and_then(|(_, text)| from_ron(text).ok())
        .map(|group| (group.group, Source::Shipped)))
}

/// Every library group's name and source (the user's first, each name once, sorted),
/// and the files of the user library that could not be read as groups.
pub fn list() -> (Vec<(String, Source)>, Vec<LoadError>) {
    let mut entries: Vec<(String, Source)> = Vec::new();
    let mut unusable = Vec::new();
    if let Some(folder) = user_folder()
        && let Ok(files) = std::fs::read_dir(&folder)
    {
        for file in files.flatten() {
            let path = file.path();
            if !path.extension().is_some_and(|e| e == "ron") {
                continue;
            }
            match load(&path) {
                Ok(group) => entries.push((group.name, Source::User(path))),
                Err(error) => unusable.push(error),
            }
        }
    }
    for (name, _) in SHIPPED {
        if !entries.iter().any(|(known, _)| known == name) {
            entries.push((name.to_string(), Source::Shipped));
        }
    }
    entries.sort_by(|a, b| a.0.cmp(&b.0));
    unusable.sort_by(|a, b| a.path.cmp(&b.path));
    (entries, unusable)
}

/// Saves `group` to the user library as `name`, replacing an older version; returns
/// the file written. A name that cannot name a file (see [`super::names`]) is refused.
pub fn save_to_user(name: &str, group: &GroupDef) -> std::io::Result<PathBuf> {
    super::names::file_name_part("group", name)
        .map_err(|message| std::io::Error::new(std::io::ErrorKind::InvalidInput, message))?;
    let folder = user_folder().ok_or_else(|| {
        std::io::Error::new(
            std::io::ErrorKind::NotFound,
            "no user library folder (set VENEER_LIBRARY or HOME)",
        )
    })?;
    std::fs::create_dir_all(&folder)?;
    let path = folder.join(format!("{name}.ron"));
    fsutil::write_atomic(&path, to_ron(name, group).as_bytes())?;
    Ok(path)
}

/// Brings every linked group of `graph` up to the library's version (keeping its copy
/// when the library has none, or a user file for it cannot be used), then resolves the
/// group nodes' pins. Returns a warning for each copy kept because of a file that
/// cannot be used, naming the file, and for each copy replaced that differed from the
/// library's (a hand edit of a linked copy would otherwise vanish unsaid).
pub fn refresh(graph: &mut Graph) -> Vec<String> {
    let mut warnings = Vec::new();
    for (name, definition) in graph.groups.iter_mut() {
        if !definition.linked {
            continue;
        }
        match find(name) {
            Ok(Some((mut current, source))) => {
                current.linked = true;
                if current != *definition {
                    let library = match &source {
                        Source::Shipped => "the one shipped with Veneer".to_string(),
                        Source::User(path) => path.display().to_string(),
                    };
                    warnings.push(format!(
                        "the graph's copy of linked group '{}' differs from the library's ({library}): the library's is used, as the group is linked; to keep the graph's copy, make the group local (Make local in the editor, or remove `linked: true` from the file)",
                        super::names::shown(name)
                    ));
                    *definition = current;
                }
            }
            Ok(None) => {}
            Err(error) => {
                let problem = match &error.path {
                    Some(_) => error.to_string(),
                    None => error.message,
                };
                warnings.push(format!(
                    "{problem}; linked group '{}' keeps the graph's copy",
                    super::names::shown(name)
                ));
            }
        }
    }
    resolve(graph);
    warnings
}

/// Adds library group `name` to `graph` (linked), unless the graph has a group of that
/// name already; the error says why the graph does not have it now.
pub fn adopt(graph: &mut Graph, name: &str) -> Result<(), String> {
    if graph.groups.contains_key(name) {
        return Ok(());
    }
    let Some((mut group, _)) = find(name).map_err(|error| error.to_string())? else {
        return Err(format!(
            "no group named '{}' in the graph or the library",
            super::names::shown(name)
        ));
    };
    group.linked = true;
    graph.groups.insert(name.to_string(), group);
    resolve(graph);
    Ok(())
}
