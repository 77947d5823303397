//! The buffers of a glTF file: the binary chunk of a GLB, `data:` URIs, and files inside
//! the glTF file's own folder, which is where the glTF specification resolves relative
//! URIs. A URI that leads anywhere else (an absolute path, a `file:` or other scheme, a
//! `..` or a link out of the folder) is refused, so that a mesh file cannot read, say,
//! `/etc/passwd` and hand it on as vertex coordinates. Images are never read.
//!
//! The check resolves links when the file is read: a folder that someone else changes
//! while Veneer reads from it is beyond it.

use crate::fsutil::{ReadLimit, read_limited};
use std::os::unix::ffi::OsStrExt;
use std::path::{Component, Path, PathBuf};

/// The data of every buffer of `document`, in order. `folder` is the glTF file's folder;
/// without one only the GLB's `blob` and `data:` URIs can be read. The files read
/// together hold at most [`ReadLimit::MESH`] bytes, however many buffers name them.
pub(super) fn import(
    document: &gltf::Document,
    folder: Option<&Path>,
    mut blob: Option<Vec<u8>>,
) -> Result<Vec<Vec<u8>>, String> {
    let mut left = ReadLimit::MESH.bytes;
    let mut buffers = Vec::new();
    for buffer in document.buffers() {
        let index = buffer.index();
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => blob.take().ok_or_else(|| {
                format!(
                    "buffer {index} refers to the binary chunk of a GLB file, but there is none"
                )
            })?,
            gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => {
                // Decoded by the glTF crate, which reads no file without a folder.
                gltf::buffer::Data::from_source(buffer.source(), None)
                    .map_err(|error| format!("buffer {index}: {error}"))?
                    .0
            }
            gltf::buffer::Source::Uri(uri) => {
                let path = inside(uri, folder)
                    .map_err(|why| format!("buffer {index}: URI '{uri}' {why}"))?;
                let limit = ReadLimit {
                    what: "the files of one glTF's buffers together",
                    bytes: left,
                };
                let data = read_limited(&path, limit).map_err(|error| {
                    format!("buffer {index}: URI '{uri}' cannot be read: {error}")
                })?;
                left -= data.len() as u64;
                data
            }
        };
        if data.len() < buffer.length() {
            return Err(format!(
                "buffer {index} holds {} bytes, but its byteLength is {}",
                data.len(),
                buffer.length()
            ));
        }
        buffers.push(data);
    }
    Ok(buffers)
}

/// The file that the relative reference `uri` (percent-encoded, as URIs are) names in
/// `folder`, with links resolved; or why it is not read ("refused: …", "cannot be read: …").
/// A `..` that climbs out of the folder is refused before any file is looked at, so that
/// the message does not tell whether a file outside exists.
fn inside(uri: &str, folder: Option<&Path>) -> Result<PathBuf, String> {
    let refused = |why: &str| Err(format!("refused: {why}"));
    let outside = "it leads outside the glTF file's folder";
    if uri.split('/').next().unwrap_or_default().contains(':') {
        return refused("only data: URIs and paths relative to the glTF file are read");
    }
    let decoded = urlencoding::decode_binary(uri.as_bytes());
    let relative = Path::new(std::ffi::OsStr::from_bytes(&decoded));
    if relative.has_root() {
        return refused("it is an absolute path; only paths relative to the glTF file are read");
    }
    let mut depth = 0usize;
    for component in relative.components() {
        match component {
            Component::ParentDir if depth == 0 => return refused(outside),
            Component::ParentDir => depth -= 1,
            Component::Normal(_) => depth += 1,
            _ => {}
        }
    }
    let folder = match folder {
        None => return refused("it names a file, but the glTF came without its folder"),
        Some(folder) if folder.as_os_str().is_empty() => Path::new("."),
        Some(folder) => folder,
    };
    let unreadable = |error: std::io::Error| format!("cannot be read: {error}");
    let folder = folder.canonicalize().map_err(unreadable)?;
    let file = folder.join(relative).canonicalize().map_err(unreadable)?;
    if !file.starts_with(&folder) {
        return refused(outside);
    }
    Ok(file)
}
