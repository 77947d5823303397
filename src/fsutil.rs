//! Files read and written safely. Reads take only regular files (after following links)
//! of a bounded size, so a graph, mesh or image that is `/dev/zero` or a FIFO is an error
//! at once instead of a read that grows without end or never returns. Writes go by what
//! the output is and never leave a half-written file behind ([`write_atomic`]); a
//! command's outputs are planned and checked before it starts ([`OutputPlan`]).

mod plan;
mod write;

pub use plan::OutputPlan;
pub use write::{
    Naming, STALE_TEMPORARY_AGE, Staged, commit, is_stream, open_stream, stage, write_atomic,
    write_atomic_with, write_implied, write_together,
};

use std::fs::{Metadata, OpenOptions};
use std::io::{self, Read};
use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
use std::path::Path;

/// `bytes` in GiB with one decimal, for messages about memory and disk.
pub fn gibibytes(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / (1u64 << 30) as f64)
}

/// The bytes an unprivileged user can still write to the file system holding `dir`,
/// when the system says.
pub fn free_space(dir: &Path) -> Option<u64> {
    use std::os::unix::ffi::OsStrExt;
    let path = std::ffi::CString::new(dir.as_os_str().as_bytes()).ok()?;
    let mut stats = std::mem::MaybeUninit::<libc::statvfs>::uninit();
    // SAFETY: `path` is a NUL-terminated string and `stats` is written by the call
    // before it is read, only when the call succeeds.
    let stats = unsafe {
        if libc::statvfs(path.as_ptr(), stats.as_mut_ptr()) != 0 {
            return None;
        }
        stats.assume_init()
    };
    Some(u64::from(stats.f_bavail).saturating_mul(u64::from(stats.f_frsize)))
}

/// The most bytes Veneer reads from one kind of file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReadLimit {
    /// The kind of file, plural, for the message (`graph files`).
    pub what: &'static str,
    pub bytes: u64,
}

impl ReadLimit {
    /// Graph files and the other RON files Veneer reads (snapshot sidecars, the editor's
    /// recovery and recent-files lists): 256 MiB. The presets are 2–12 KiB and a graph
    /// takes 150–200 bytes a node, so this is well over a million nodes — the largest
    /// graphs `veneer check` is measured on (a 10⁶-node chain is a 190 MB file, read and
    /// parsed in about 4 s, 2.3 GB at its peak) — and far past what a shader can use.
    pub const GRAPH: ReadLimit = ReadLimit {
        what: "graph files",
        bytes: 256 << 20,
    };
    /// Mesh files, and the buffers of one glTF file together: 2 GiB. A binary STL of
    /// 2 GiB holds 42 million triangles (an OBJ about 30 million), beyond what the
    /// 32-bit indices of a render's vertex buffers and a preview can usefully take, and
    /// the file and the mesh parsed from it still fit in the memory of a workstation.
    pub const MESH: ReadLimit = ReadLimit {
        what: "mesh files",
        bytes: 2 << 30,
    };
    /// Golden PNG images of snapshot tests: 1 GiB, the size of an uncompressed
    /// 16384×16384 RGBA image, the largest texture most adapters can render.
    pub const IMAGE: ReadLimit = ReadLimit {
        what: "images",
        bytes: 1 << 30,
    };
}

/// Reads the whole of `path`, which must be a regular file (links are followed) of at
/// most `limit` bytes. A FIFO, device, socket or folder is refused without waiting for
/// data, and so is a file larger than the limit (or one that grows past it while it is
/// read); the error says which.
pub fn read_limited(path: &Path, limit: ReadLimit) -> io::Result<Vec<u8>> {
    // Asking first gives sockets (which cannot be opened) the same message as the rest;
    // the open file is asked again, as the path may have changed in between.
    regular(&std::fs::metadata(path)?, limit)?;
    // Without O_NONBLOCK, opening a FIFO waits for a writer; regular files ignore it.
    let file = OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)?;
    let metadata = file.metadata()?;
    regular(&metadata, limit)?;
    let mut bytes = Vec::with_capacity(metadata.len() as usize);
    file.take(limit.bytes + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit.bytes {
        return Err(too_large(limit));
    }
    Ok(bytes)
}

/// Refuses what is not a regular file or is larger than `limit`.
fn regular(metadata: &Metadata, limit: ReadLimit) -> io::Result<()> {
    if !metadata.is_file() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("it is {}, not a regular file", what_it_is(metadata)),
        ));
    }
    if metadata.len() > limit.bytes {
        return Err(too_large(limit));
    }
    Ok(())
}

/// What a file is, for messages: `a folder`, `a FIFO (named pipe)`, … (`metadata` from
/// `symlink_metadata` can also say `a symbolic link`).
fn what_it_is(metadata: &Metadata) -> &'static str {
    let kind = metadata.file_type();
    if kind.is_dir() {
        "a folder"
    } else if kind.is_symlink() {
        "a symbolic link"
    } else if kind.is_fifo() {
        "a FIFO (named pipe)"
    } else if kind.is_char_device() {
        "a character device"
    } else if kind.is_block_device() {
        "a block device"
    } else if kind.is_socket() {
        "a socket"
    } else {
        "a regular file"
    }
}

fn too_large(limit: ReadLimit) -> io::Error {
    let size = match limit.bytes {
        bytes if bytes >= 1 << 30 && bytes % (1 << 30) == 0 => format!("{} GiB", bytes >> 30),
        bytes if bytes >= 1 << 20 && bytes % (1 << 20) == 0 => format!("{} MiB", bytes >> 20),
        bytes => format!("{bytes} bytes"),
    };
    io::Error::new(
        io::ErrorKind::FileTooLarge,
        format!(
            "the file is larger than {size}, the limit for {}",
            limit.what
        ),
    )
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A fresh folder for one test.
    pub(crate) fn folder(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("veneer-fsutil-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    pub(crate) fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    /// Runs `f` on a thread of its own and gives its result, failing the test when it
    /// has not returned within 30 s (a write that blocks, not a slow one).
    pub(crate) fn returns<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
        let (done, result) = std::sync::mpsc::channel();
        std::thread::spawn(move || done.send(f()));
        result
            .recv_timeout(std::time::Duration::from_secs(30))
            .expect("returned within 30 s instead of blocking")
    }

    /// Makes a FIFO at `path`.
    pub(crate) fn mkfifo(path: &Path) {
        use std::os::unix::ffi::OsStrExt;
        let name = std::ffi::CString::new(path.as_os_str().as_bytes()).unwrap();
        // SAFETY: `name` is a NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
    }

    #[test]
    fn special_files_and_files_over_the_limit_are_refused_at_once() {
        let dir = folder("read");
        let tiny = ReadLimit {
            what: "tests",
            bytes: 4,
        };
        std::fs::write(dir.join("small"), "1234").unwrap();
        assert_eq!(read_limited(&dir.join("small"), tiny).unwrap(), b"1234");
        std::fs::write(dir.join("large"), "12345").unwrap();
        let error = read_limited(&dir.join("large"), tiny).unwrap_err();
        assert_eq!(error.kind(), io::ErrorKind::FileTooLarge);
        assert!(error.to_string().contains("the limit for tests"), "{error}");
        let zero = read_limited(Path::new("/dev/zero"), tiny).unwrap_err();
        assert!(zero.to_string().contains("a character device"), "{zero}");
        let folder_error = read_limited(&dir, tiny).unwrap_err();
        assert!(
            folder_error.to_string().contains("a folder"),
            "{folder_error}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
