//! Files read and written safely. Reads take only regular files (after following links)
//! of a bounded size, so a graph, mesh or image that is `/dev/zero` or a FIFO is an error
//! at once instead of a read that grows without end or never returns. Writes never leave
//! a half-written file behind: they go to a temporary file created exclusively under an
//! unpredictable name (`.veneer-XXXXXX.tmp`) in the target's folder, which takes the old
//! file's mode and owner and is then renamed over the target.
//!
//! A temporary file is removed when its write fails; one left by a Veneer that was killed
//! mid-write is removed by a later write to the same folder once it has not been modified
//! for [`STALE_TEMPORARY_AGE`] (and only when it is a regular file owned by the same user).

use std::fs::{File, Metadata, OpenOptions};
use std::io::{self, Read, Write};
use std::os::unix::fs::{FileTypeExt, MetadataExt, OpenOptionsExt, PermissionsExt};
use std::path::Path;
use std::time::Duration;

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
    let kind = metadata.file_type();
    let other = if kind.is_dir() {
        "a folder"
    } else if kind.is_fifo() {
        "a FIFO (named pipe)"
    } else if kind.is_char_device() {
        "a character device"
    } else if kind.is_block_device() {
        "a block device"
    } else if kind.is_socket() {
        "a socket"
    } else if metadata.len() > limit.bytes {
        return Err(too_large(limit));
    } else {
        return Ok(());
    };
    Err(io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("it is {other}, not a regular file"),
    ))
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

/// How long a temporary file of ours may go unmodified before a later write to its
/// folder takes it for the leftover of a killed Veneer and removes it: a day. A live
/// write modifies its temporary file as it goes, and takes seconds.
pub const STALE_TEMPORARY_AGE: Duration = Duration::from_secs(24 * 60 * 60);

const TEMPORARY_PREFIX: &str = ".veneer-";
const TEMPORARY_SUFFIX: &str = ".tmp";

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename,
/// so that readers see either the old file or the whole new one. A failed write (full
/// disk, no permission) removes the temporary file and says that the old file, if there
/// was one, is unchanged.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic_with(path, |file| file.write_all(bytes))
}

/// Like [`write_atomic`], but `write` streams the content into the temporary file (for
/// outputs too large to hold twice in memory). A path that names something other than
/// a regular file (`/dev/stdout`, a pipe) is written in place: renaming over it would
/// replace the device with a file. Writing through a link replaces what it points to and
/// keeps the link. The new file keeps the old one's mode, and its owner and group where
/// this process may set them.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut io::BufWriter<File>) -> io::Result<()>,
) -> io::Result<()> {
    let special = path.starts_with("/dev")
        || path.starts_with("/proc")
        || std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir());
    if special {
        let mut file = io::BufWriter::new(OpenOptions::new().write(true).open(path)?);
        write(&mut file)?;
        return file
            .into_inner()
            .map(drop)
            .map_err(|error| error.into_error());
    }
    // Replace what a link points to, not the link.
    let resolved;
    let path = if std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink()) {
        resolved = std::fs::canonicalize(path)?;
        resolved.as_path()
    } else {
        path
    };
    replace(path, write).map_err(|error| {
        let kept = if path.exists() {
            "the old file is unchanged"
        } else {
            "nothing was written"
        };
        io::Error::new(error.kind(), format!("{error}; {kept}"))
    })
}

/// Writes a new file beside `path` and renames it over `path`; the temporary file is
/// removed when any step fails (dropping its `TempPath` removes it).
fn replace(
    path: &Path,
    write: impl FnOnce(&mut io::BufWriter<File>) -> io::Result<()>,
) -> io::Result<()> {
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    let old = std::fs::metadata(path).ok().filter(Metadata::is_file);
    // Created with no more permission than the old file had (or what a new file gets
    // under the umask), so the content is never readable by more users than before.
    let mode = old.as_ref().map_or(0o666, |old| old.mode() & 0o777);
    let (file, temporary) = tempfile::Builder::new()
        .prefix(TEMPORARY_PREFIX)
        .suffix(TEMPORARY_SUFFIX)
        .make_in(dir, |name| {
            OpenOptions::new()
                .write(true)
                .create_new(true)
                .mode(mode)
                .open(name)
        })?
        .into_parts();
    remove_stale_temporaries(dir, file.metadata()?.uid());
    if let Some(old) = &old {
        keep_owner_and_mode(&file, old)?;
    }
    let mut writer = io::BufWriter::new(file);
    write(&mut writer)?;
    writer
        .into_inner()
        .map_err(|error| error.into_error())?
        .sync_all()?;
    temporary.persist(path).map_err(|error| error.error)
}

/// Gives the new file the old one's owner and group (or only its group, or neither,
/// where this process may not: EPERM is not an error), then its mode, set last because
/// changing the owner clears the set-user-ID bit.
fn keep_owner_and_mode(file: &File, old: &Metadata) -> io::Result<()> {
    use std::os::unix::fs::fchown;
    let permitted = |result: io::Result<()>| match result {
        Err(error) if error.kind() == io::ErrorKind::PermissionDenied => Ok(false),
        result => result.map(|()| true),
    };
    if !permitted(fchown(file, Some(old.uid()), Some(old.gid())))? {
        permitted(fchown(file, None, Some(old.gid())))?;
    }
    file.set_permissions(std::fs::Permissions::from_mode(old.mode() & 0o7777))
}

/// Removes our temporary files in `dir` (regular files owned by `uid`, named like ours)
/// that have not been modified for [`STALE_TEMPORARY_AGE`]. Best effort: what cannot be
/// read or removed is left.
fn remove_stale_temporaries(dir: &Path, uid: u32) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if !(name.starts_with(TEMPORARY_PREFIX) && name.ends_with(TEMPORARY_SUFFIX)) {
            continue;
        }
        // Not following links: a link named like ours is someone else's.
        let Ok(metadata) = entry.metadata() else {
            continue;
        };
        let stale = metadata
            .modified()
            .ok()
            .and_then(|time| time.elapsed().ok())
            .is_some_and(|age| age > STALE_TEMPORARY_AGE);
        if metadata.is_file() && metadata.uid() == uid && stale {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh folder for one test.
    fn folder(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("veneer-fsutil-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn writing_through_a_link_replaces_its_target_and_keeps_the_link() {
        let dir = folder("link");
        let (target, link) = (dir.join("target.txt"), dir.join("link.txt"));
        std::fs::write(&target, "old").unwrap();
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        assert_eq!(names(&dir), ["link.txt", "target.txt"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_rewritten_file_keeps_its_mode() {
        let dir = folder("mode");
        let path = dir.join("private.ron");
        std::fs::write(&path, "old").unwrap();
        for mode in [0o600, 0o640, 0o444] {
            std::fs::set_permissions(&path, std::fs::Permissions::from_mode(mode)).unwrap();
            write_atomic(&path, b"new").unwrap();
            let metadata = std::fs::metadata(&path).unwrap();
            assert_eq!(metadata.mode() & 0o7777, mode);
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn stale_temporaries_of_ours_are_removed_and_fresh_ones_and_others_kept() {
        let dir = folder("stale");
        let old = std::time::SystemTime::now() - STALE_TEMPORARY_AGE * 2;
        for name in [
            ".veneer-stale1.tmp",
            ".other-stale.tmp",
            "keep.veneer-x.tmp",
        ] {
            File::create(dir.join(name))
                .unwrap()
                .set_modified(old)
                .unwrap();
        }
        File::create(dir.join(".veneer-fresh1.tmp")).unwrap();
        std::os::unix::fs::symlink("/nowhere", dir.join(".veneer-link01.tmp")).unwrap();
        write_atomic(&dir.join("out.txt"), b"new").unwrap();
        assert_eq!(
            names(&dir),
            [
                ".other-stale.tmp",
                ".veneer-fresh1.tmp",
                ".veneer-link01.tmp",
                "keep.veneer-x.tmp",
                "out.txt"
            ]
        );
        std::fs::remove_dir_all(&dir).unwrap();
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
