//! Writing outputs by what they are, not by their path. A regular file (anywhere,
//! `/dev/shm` included) is never written in place: it goes to a temporary file created
//! exclusively under an unpredictable name (`.veneer-XXXXXX.tmp`) in the target's folder,
//! which takes the old file's mode and owner and is then renamed over the target, so
//! readers see the old file or the whole new one. A character device (`/dev/null`,
//! `/dev/stdout`) is written in place; a FIFO is opened without waiting and written only
//! when a reader has it open — without one it is refused at once instead of blocking.
//! Files Veneer names itself ([`Naming::Implied`]) are written only as regular files of
//! their own, never through a link.
//!
//! Outputs written together ([`stage`], then [`commit`]) go to their temporary files
//! first and are renamed into place only when all are written, so a failed multi-file
//! export leaves none of its files behind.
//!
//! A temporary file is removed when its write fails; one left by a Veneer that was killed
//! mid-write is removed by a later write to the same folder once it has not been modified
//! for [`STALE_TEMPORARY_AGE`] (and only when it is a regular file owned by the same user).

use super::what_it_is;
use std::fs::{File, Metadata, OpenOptions};
use std::io::{self, Write};
use std::os::unix::fs::{FileTypeExt, MetadataExt, OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Who named a file Veneer writes, which decides what may stand at its path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Naming {
    /// The user named it (`-o`, `--write`, `--gltf`, `--frame-log`, a file dialog). It is
    /// written by what it is: a regular file, or a link to one, is replaced through a
    /// temporary file (the link kept); a character device is written in place; a FIFO only
    /// while a reader has it open; a folder, block device or socket is refused.
    Given,
    /// Veneer named it: a map or texture beside the named output, a parameter description,
    /// a golden and the images beside it, a report's files, the editor's recovery files
    /// and recent list. It is written only as a regular file of its own: anything else at
    /// its path (a symbolic link, a FIFO, a device, a folder) is refused and left alone.
    Implied,
}

/// How long a temporary file of ours may go unmodified before a later write to its
/// folder takes it for the leftover of a killed Veneer and removes it: a day. A live
/// write modifies its temporary file as it goes, and takes seconds.
pub const STALE_TEMPORARY_AGE: Duration = Duration::from_secs(24 * 60 * 60);

const TEMPORARY_PREFIX: &str = ".veneer-";
const TEMPORARY_SUFFIX: &str = ".tmp";

/// Writes `bytes` to `path`, which the user named (see [`Naming::Given`]): a regular file
/// through a temporary file and a rename, so that readers see either the old file or the
/// whole new one. A failed write (full disk, no permission) removes the temporary file
/// and says that the old file, if there was one, is unchanged.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic_with(path, Naming::Given, |file| file.write_all(bytes))
}

/// Writes `bytes` to `path`, a file Veneer named itself (see [`Naming::Implied`]).
pub fn write_implied(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic_with(path, Naming::Implied, |file| file.write_all(bytes))
}

/// Like [`write_atomic`], for either [`Naming`], with `write` streaming the content (for
/// outputs too large to hold twice in memory).
pub fn write_atomic_with(
    path: &Path,
    naming: Naming,
    write: impl FnOnce(&mut io::BufWriter<File>) -> io::Result<()>,
) -> io::Result<()> {
    commit(vec![stage(path, naming, write)?]).map_err(|(_, error)| error)
}

/// Writes several outputs together: each to its temporary file ([`stage`]), then all
/// into place ([`commit`]), so that when any cannot be written none appears. The error
/// comes with the path that failed.
pub fn write_together<'a>(
    files: impl IntoIterator<Item = (&'a Path, Naming, &'a [u8])>,
) -> Result<(), (PathBuf, io::Error)> {
    let mut staged = Vec::new();
    for (path, naming, bytes) in files {
        let file = stage(path, naming, |file| file.write_all(bytes));
        staged.push(file.map_err(|error| (path.to_path_buf(), error))?);
    }
    commit(staged)
}

/// An output written but not yet in place: its temporary file, renamed over its target
/// by [`commit`] and removed if the `Staged` is dropped instead. (A stream — a character
/// device or FIFO — is written at once and has nothing left to do.)
pub struct Staged(Option<Pending>);

struct Pending {
    temporary: tempfile::TempPath,
    target: PathBuf,
    /// Whether a file stood at the target before.
    existed: bool,
}

/// Writes the output at `path`: a regular file into a temporary file beside it, put in
/// place by [`commit`]; a character device or a FIFO with a reader at once. Errors say
/// what became of the old file.
pub fn stage(
    path: &Path,
    naming: Naming,
    write: impl FnOnce(&mut io::BufWriter<File>) -> io::Result<()>,
) -> io::Result<Staged> {
    match route(path, naming)? {
        Route::Stream(file) => {
            let mut writer = io::BufWriter::new(file);
            write(&mut writer)?;
            writer.into_inner().map_err(|error| error.into_error())?;
            Ok(Staged(None))
        }
        Route::Replace(target) => {
            let existed = std::fs::symlink_metadata(&target).is_ok();
            let temporary = temporary_beside(&target, write).map_err(|error| {
                let kept = if existed {
                    "the old file is unchanged"
                } else {
                    "nothing was written"
                };
                io::Error::new(error.kind(), format!("{error}; {kept}"))
            })?;
            Ok(Staged(Some(Pending {
                temporary,
                target,
                existed,
            })))
        }
    }
}

/// Puts staged outputs in place, in order. When one cannot be, the files put in place
/// before it that are new are removed again and the rest are dropped (their temporary
/// files removed): what was there before stays, but for files already replaced, which
/// the error lists. The error comes with the path that failed.
pub fn commit(files: Vec<Staged>) -> Result<(), (PathBuf, io::Error)> {
    let mut done: Vec<(PathBuf, bool)> = Vec::new();
    for Pending {
        temporary,
        target,
        existed,
    } in files.into_iter().filter_map(|staged| staged.0)
    {
        if let Err(error) = temporary.persist(&target) {
            let mut replaced = Vec::new();
            for (path, existed) in done {
                if existed {
                    replaced.push(path.display().to_string());
                } else {
                    let _ = std::fs::remove_file(&path);
                }
            }
            let kept = if existed {
                "the old file is unchanged"
            } else {
                "nothing was written there"
            };
            let also = match replaced.is_empty() {
                true => String::new(),
                false => format!("; already replaced: {}", replaced.join(", ")),
            };
            let error = error.error;
            return Err((
                target,
                io::Error::new(error.kind(), format!("{error}; {kept}{also}")),
            ));
        }
        done.push((target, existed));
    }
    Ok(())
}

/// How an output is written.
enum Route {
    /// Through a temporary file renamed over this path: the output, or the file a link
    /// the user named points to.
    Replace(PathBuf),
    /// In place: a character device or a FIFO with a reader, opened.
    Stream(File),
}

/// What the output at `path` is, and so how it is written.
fn route(path: &Path, naming: Naming) -> io::Result<Route> {
    let entry = match std::fs::symlink_metadata(path) {
        Err(error) if error.kind() == io::ErrorKind::NotFound => {
            return Ok(Route::Replace(path.to_path_buf()));
        }
        entry => entry?,
    };
    if entry.is_file() {
        return Ok(Route::Replace(path.to_path_buf()));
    }
    if naming == Naming::Implied {
        return Err(not_own_file(&entry));
    }
    let target = match std::fs::metadata(path) {
        Err(error) if error.kind() == io::ErrorKind::NotFound => {
            return Err(refused("it is a link to a file that does not exist"));
        }
        target => target?,
    };
    let kind = target.file_type();
    if target.is_file() {
        // Replace what a link points to, not the link.
        Ok(Route::Replace(std::fs::canonicalize(path)?))
    } else if kind.is_char_device() || kind.is_fifo() {
        open_stream(path).map(Route::Stream)
    } else {
        Err(refused(format!(
            "it is {}; Veneer writes regular files, character devices and FIFOs",
            what_it_is(&target)
        )))
    }
}

/// Whether `path` (links followed) is a stream — a character device or a FIFO — which is
/// written in order rather than replaced, and beside which nothing is put.
pub fn is_stream(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|found| {
        let kind = found.file_type();
        kind.is_char_device() || kind.is_fifo()
    })
}

/// The refusal of a file Veneer names itself that is not a regular file at its path
/// (`entry`: its metadata, links not followed); the output plan refuses with it too.
pub(super) fn not_own_file(entry: &Metadata) -> io::Error {
    refused(format!(
        "it is {}, and Veneer writes the files it names itself only as regular files \
         (remove it, or write elsewhere)",
        what_it_is(entry)
    ))
}

fn refused(message: impl Into<String>) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message.into())
}

/// Opens `path` to be written as a stream, by what it is: a regular file (created when
/// missing) is emptied; a character device is opened as it is; a FIFO only when a reader
/// has it open — opening does not wait for one, and without one the answer is an error
/// at once. Anything else is refused. Writes then wait for the reader, as on any pipe.
pub fn open_stream(path: &Path) -> io::Result<File> {
    let file = OpenOptions::new()
        .write(true)
        .create(true)
        .custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY)
        .open(path)
        .map_err(|error| match error.raw_os_error() {
            Some(libc::ENXIO) => refused(
                "it is a FIFO (named pipe) with no reader; start the program that reads it first",
            ),
            _ => error,
        })?;
    let metadata = file.metadata()?;
    let kind = metadata.file_type();
    if metadata.is_file() {
        file.set_len(0)?;
    } else if !(kind.is_char_device() || kind.is_fifo()) {
        return Err(refused(format!(
            "it is {}; Veneer writes regular files, character devices and FIFOs",
            what_it_is(&metadata)
        )));
    }
    blocking(&file)?;
    Ok(file)
}

/// Clears `O_NONBLOCK` on `file`.
fn blocking(file: &File) -> io::Result<()> {
    use std::os::fd::AsRawFd;
    let fd = file.as_raw_fd();
    // SAFETY: F_GETFL and F_SETFL on a descriptor `file` owns for the whole call.
    let ok = unsafe {
        let flags = libc::fcntl(fd, libc::F_GETFL);
        flags >= 0 && libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK) == 0
    };
    if ok {
        Ok(())
    } else {
        Err(io::Error::last_os_error())
    }
}

/// Writes a new file beside `path` through `write`, synced, under a temporary name;
/// dropping the returned path removes it, as does any failure here.
fn temporary_beside(
    path: &Path,
    write: impl FnOnce(&mut io::BufWriter<File>) -> io::Result<()>,
) -> io::Result<tempfile::TempPath> {
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
    Ok(temporary)
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
    use crate::fsutil::tests::{folder, mkfifo, names, returns};

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
    fn a_fifo_without_a_reader_is_refused_at_once() {
        let dir = folder("fifo");
        let fifo = dir.join("out.wgsl");
        mkfifo(&fifo);
        let written = returns(move || write_atomic(&fifo, b"new"));
        let error = written.unwrap_err();
        assert!(
            error
                .to_string()
                .contains("a FIFO (named pipe) with no reader"),
            "{error}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn regular_files_under_dev_shm_are_replaced_whole() {
        let shm = Path::new("/dev/shm");
        assert!(shm.is_dir(), "this test needs /dev/shm");
        let path = shm.join(format!("veneer-fsutil-{}.txt", std::process::id()));
        std::fs::write(&path, "a longer old file").unwrap();
        write_atomic(&path, b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        std::fs::remove_file(&path).unwrap();
    }

    #[test]
    fn character_devices_are_written_in_place_and_say_why_they_fail() {
        write_atomic(Path::new("/dev/null"), b"new").unwrap();
        let error = write_atomic(Path::new("/dev/full"), b"new").unwrap_err();
        assert_eq!(error.raw_os_error(), Some(libc::ENOSPC), "{error}");
    }

    #[test]
    fn implied_files_are_never_written_through_links_nor_into_special_files() {
        let dir = folder("implied");
        let (victim, link) = (dir.join("victim.txt"), dir.join("out_basecolor.png"));
        std::fs::write(&victim, "precious").unwrap();
        std::os::unix::fs::symlink(&victim, &link).unwrap();
        let error = write_implied(&link, b"new").unwrap_err();
        assert!(
            error.to_string().contains("it is a symbolic link"),
            "{error}"
        );
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
        mkfifo(&dir.join("recent.ron"));
        let fifo = dir.join("recent.ron");
        let error = returns(move || write_implied(&fifo, b"new")).unwrap_err();
        assert!(error.to_string().contains("it is a FIFO"), "{error}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_set_that_fails_midway_removes_the_new_files_and_keeps_the_old() {
        let dir = folder("set");
        let path = |name: &str| dir.join(name);
        std::fs::write(path("old.txt"), "old").unwrap();
        std::fs::write(path("other.txt"), "not ours").unwrap();
        let staged = |name: &str| {
            stage(&path(name), Naming::Implied, |file| file.write_all(b"new")).unwrap()
        };
        let set = vec![staged("new.txt"), staged("old.txt"), staged("blocked")];
        // A folder in the way of the last rename (it was not there when it was staged).
        std::fs::create_dir_all(path("blocked/inside")).unwrap();
        let (failed, error) = commit(set).unwrap_err();
        assert_eq!(failed, path("blocked"));
        assert!(error.to_string().contains("already replaced"), "{error}");
        assert!(!path("new.txt").exists(), "the new file is removed again");
        assert_eq!(std::fs::read_to_string(path("old.txt")).unwrap(), "new");
        assert_eq!(
            std::fs::read_to_string(path("other.txt")).unwrap(),
            "not ours"
        );
        assert_eq!(
            names(&dir),
            ["blocked", "old.txt", "other.txt"],
            "no temporary left"
        );
        // Dropped before it is committed: nothing was written.
        drop(vec![staged("dropped.txt")]);
        assert_eq!(names(&dir), ["blocked", "old.txt", "other.txt"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
