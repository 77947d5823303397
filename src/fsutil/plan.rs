//! The output plan of a command (or of a whole batch): every file it will write, the
//! side files it names itself included, listed before any work starts and checked
//! against every file it reads and against each other. An output that is one of the
//! inputs, or that two writers share, is refused with both names; so is a file Veneer
//! names itself that stands at its path as a link, FIFO, device or folder.
//!
//! Paths are compared as files, not as strings: by device and inode when the file
//! exists, else by where it would be created (its existing folder resolved, links and
//! `..` followed). Streams — character devices and FIFOs — are written in order, not
//! replaced, so two writers may share one (`/dev/null`).

use super::Naming;
use std::collections::HashMap;
use std::os::unix::fs::MetadataExt;
use std::path::{Component, Path, PathBuf};

/// What a command (or batch) reads and writes.
#[derive(Debug, Default)]
pub struct OutputPlan {
    reads: Vec<Entry>,
    writes: Vec<(Entry, Naming)>,
}

#[derive(Debug)]
struct Entry {
    path: PathBuf,
    /// Who reads or writes it: a graph, a batch's job (`job 2 (render a.ron)`).
    by: String,
}

impl OutputPlan {
    /// An empty plan.
    pub fn new() -> OutputPlan {
        OutputPlan::default()
    }

    /// Notes that `by` reads `path`.
    pub fn reads(&mut self, path: impl AsRef<Path>, by: &str) {
        self.reads.push(Entry {
            path: path.as_ref().to_path_buf(),
            by: by.to_string(),
        });
    }

    /// Notes that `by` writes `path`, named as `naming` says.
    pub fn writes(&mut self, path: impl AsRef<Path>, naming: Naming, by: &str) {
        let entry = Entry {
            path: path.as_ref().to_path_buf(),
            by: by.to_string(),
        };
        self.writes.push((entry, naming));
    }

    /// Notes that `by` writes `files`: the first the file the user named, the rest
    /// named by Veneer beside it (a document and its textures).
    pub fn writes_beside(&mut self, files: &[std::path::PathBuf], by: &str) {
        for (index, path) in files.iter().enumerate() {
            let naming = if index == 0 {
                Naming::Given
            } else {
                Naming::Implied
            };
            self.writes(path, naming, by);
        }
    }

    /// The first problem of the plan, as a message naming the files (and their writers
    /// when they differ): a file Veneer names itself that is not a regular file of its
    /// own, an output that is an input, an output written twice.
    pub fn check(&self) -> Result<(), String> {
        for (entry, naming) in &self.writes {
            if *naming == Naming::Implied
                && let Ok(found) = std::fs::symlink_metadata(&entry.path)
                && !found.is_file()
            {
                let error = super::write::not_own_file(&found);
                return Err(format!("{}: cannot write: {error}", entry.path.display()));
            }
        }
        let mut reads: HashMap<Identity, &Entry> = HashMap::new();
        for entry in &self.reads {
            if let Some(id) = identity(&entry.path) {
                reads.entry(id).or_insert(entry);
            }
        }
        let mut written: HashMap<Identity, &Entry> = HashMap::new();
        for (output, _) in &self.writes {
            let Some(id) = identity(&output.path) else {
                continue;
            };
            if let Some(input) = reads.get(&id) {
                return Err(replaces_input(output, input));
            }
            if let Some(first) = written.get(&id) {
                return Err(written_twice(first, output));
            }
            written.insert(id, output);
        }
        Ok(())
    }
}

fn replaces_input(output: &Entry, input: &Entry) -> String {
    let named = match output.path == input.path {
        true => String::new(),
        false => format!(" {}", input.path.display()),
    };
    let what = if output.by == input.by {
        format!("this output would replace the input{named}")
    } else {
        format!(
            "this output of {} would replace the input{named} of {}",
            output.by, input.by
        )
    };
    format!(
        "{}: {what}; choose another output (nothing was done)",
        output.path.display()
    )
}

fn written_twice(first: &Entry, second: &Entry) -> String {
    let who = if first.by == second.by {
        format!("{} would write this file twice", first.by)
    } else {
        format!("both {} and {} would write this file", first.by, second.by)
    };
    let named = match first.path == second.path {
        true => String::new(),
        false => format!(" (the second as {})", second.path.display()),
    };
    format!(
        "{}: {who}{named}; give each output its own name (nothing was done)",
        first.path.display()
    )
}

/// Which file a path is, for telling two paths to one file apart from two files.
#[derive(Debug, PartialEq, Eq, Hash)]
enum Identity {
    /// An existing file: its device and inode.
    File(u64, u64),
    /// A file still to be created: where, with its folder resolved as far as it exists.
    Location(PathBuf),
}

/// The identity of `path`; `None` for a stream (a character device or FIFO).
fn identity(path: &Path) -> Option<Identity> {
    if super::is_stream(path) {
        return None;
    }
    match std::fs::metadata(path) {
        Ok(found) => Some(Identity::File(found.dev(), found.ino())),
        Err(_) => Some(Identity::Location(location(path))),
    }
}

/// Where a file at `path` would be created: the path made absolute and resolved
/// component by component as far as it exists (links followed), `.` dropped and `..`
/// taking off the component before it.
fn location(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut resolved = PathBuf::new();
    for component in absolute.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                resolved.pop();
            }
            other => {
                resolved.push(other);
                if let Ok(real) = std::fs::canonicalize(&resolved) {
                    resolved = real;
                }
            }
        }
    }
    resolved
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(reads: &[&str], writes: &[(&str, &str)]) -> OutputPlan {
        let mut plan = OutputPlan::new();
        for path in reads {
            plan.reads(path, "compile");
        }
        for (path, by) in writes {
            plan.writes(path, Naming::Given, by);
        }
        plan
    }

    #[test]
    fn paths_to_one_file_are_one_output() {
        let dir = tempfile::tempdir().unwrap();
        let d = |name: &str| dir.path().join(name).to_string_lossy().into_owned();
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        std::fs::write(dir.path().join("g.ron"), "graph").unwrap();
        std::os::unix::fs::symlink(dir.path().join("g.ron"), dir.path().join("link.ron")).unwrap();
        for output in ["g.ron", "sub/../g.ron", "./g.ron", "link.ron"] {
            let error = plan(&[&d("g.ron")], &[(&d(output), "compile")])
                .check()
                .unwrap_err();
            assert!(
                error.contains("this output would replace the input"),
                "{error}"
            );
        }
        // Not yet there: compared by where they would be created.
        let error = plan(
            &[],
            &[
                (&d("new.wgsl"), "job 1"),
                (&d("sub/.././new.wgsl"), "job 2"),
            ],
        )
        .check()
        .unwrap_err();
        assert!(
            error.contains("both job 1 and job 2 would write this file"),
            "{error}"
        );
        let error = plan(&[], &[(&d("a/b/x"), "job 1"), (&d("a/c/../b/x"), "job 2")])
            .check()
            .unwrap_err();
        assert!(error.contains("(the second as "), "{error}");
        assert!(
            plan(
                &[&d("g.ron")],
                &[(&d("sub/g.ron"), "compile"), (&d("h"), "x")]
            )
            .check()
            .is_ok()
        );
        // Streams are shared.
        assert!(
            plan(&[], &[("/dev/null", "job 1"), ("/dev/null", "job 2")])
                .check()
                .is_ok()
        );
    }

    #[test]
    fn implied_files_must_be_regular_files_of_their_own() {
        let dir = tempfile::tempdir().unwrap();
        let link = dir.path().join("out_basecolor.png");
        std::os::unix::fs::symlink("/nowhere", &link).unwrap();
        let mut plan = OutputPlan::new();
        plan.writes(&link, Naming::Given, "bake");
        assert!(plan.check().is_ok(), "a link the user names is followed");
        plan.writes(&link, Naming::Implied, "bake");
        let error = plan.check().unwrap_err();
        assert!(error.contains("it is a symbolic link"), "{error}");
    }
}
