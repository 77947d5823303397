//! Where an Image node's file is: its path as the graph stores it, relative to the
//! graph file's folder, resolved and checked. The path may climb out of the folder with
//! `..` as written (a project's shared `assets/` folder), but a link may not lead
//! anywhere the written path does not reach by itself: a graph can read, say,
//! `textures/stone.png`, never `/etc/passwd` through a link named `textures`.

use std::path::{Component, Path, PathBuf};

/// The file `written` names relative to `folder` (the graph file's folder), links
/// resolved; or why it cannot be read. An absolute path is refused (it would not move
/// with the graph), and so is a path whose links lead out of the folder its `..`s reach.
pub fn resolve(folder: &Path, written: &str) -> Result<PathBuf, String> {
    if written.trim().is_empty() {
        return Err("no file chosen".to_string());
    }
    let relative = Path::new(written);
    if relative.has_root() {
        return Err(
            "it is an absolute path; image paths are stored relative to the graph's folder"
                .to_string(),
        );
    }
    // The folder the written path reaches up to: the graph's, climbed by its `..`s.
    let (mut depth, mut climb) = (0i64, 0i64);
    for component in relative.components() {
        match component {
            Component::ParentDir => depth -= 1,
            Component::Normal(_) => depth += 1,
            _ => {}
        }
        climb = climb.max(-depth);
    }
    let folder = if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    };
    let mut reach = folder.to_path_buf();
    for _ in 0..climb {
        reach.push("..");
    }
    let unreadable = |error: std::io::Error| format!("cannot be read: {error}");
    let reach = reach.canonicalize().map_err(unreadable)?;
    let file = folder.join(relative).canonicalize().map_err(unreadable)?;
    if !file.starts_with(&reach) {
        return Err(format!(
            "refused: a link leads it out of {}, the folder its path stays in",
            reach.display()
        ));
    }
    Ok(file)
}

/// `target` written relative to `folder` (both as given, made absolute against the
/// current folder): what the editor stores when a file is chosen, climbing with `..`
/// where the file is outside the folder.
pub fn relative_to(folder: &Path, target: &Path) -> PathBuf {
    let absolute = |path: &Path| {
        let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
        // Lexically: `a/./b/../c` as `a/c`.
        let mut clean = PathBuf::new();
        for component in path.components() {
            match component {
                Component::ParentDir => {
                    clean.pop();
                }
                Component::CurDir => {}
                other => clean.push(other),
            }
        }
        clean
    };
    let (folder, target) = (absolute(folder), absolute(target));
    let shared = (folder.components())
        .zip(target.components())
        .take_while(|(a, b)| a == b)
        .count();
    let mut relative = PathBuf::new();
    for _ in shared..folder.components().count() {
        relative.push("..");
    }
    for component in target.components().skip(shared) {
        relative.push(component);
    }
    relative
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("veneer-bitmap-path-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("graphs/textures")).unwrap();
        std::fs::create_dir_all(dir.join("assets")).unwrap();
        std::fs::write(dir.join("assets/photo.png"), b"x").unwrap();
        std::fs::write(dir.join("graphs/textures/mask.png"), b"x").unwrap();
        std::fs::write(dir.join("secret.png"), b"x").unwrap();
        dir
    }

    #[test]
    fn paths_resolve_inside_the_folder_and_up_through_written_parents() {
        let dir = folder("inside");
        let graphs = dir.join("graphs");
        let mask = resolve(&graphs, "textures/mask.png").unwrap();
        assert!(mask.ends_with("graphs/textures/mask.png"));
        let photo = resolve(&graphs, "../assets/photo.png").unwrap();
        assert!(photo.ends_with("assets/photo.png"));
    }

    #[test]
    fn absolute_paths_missing_files_and_links_out_are_refused() {
        let dir = folder("refused");
        let graphs = dir.join("graphs");
        let absolute = dir.join("secret.png");
        let error = resolve(&graphs, absolute.to_str().unwrap()).unwrap_err();
        assert!(error.contains("absolute path"), "{error}");
        let error = resolve(&graphs, "textures/none.png").unwrap_err();
        assert!(error.contains("cannot be read"), "{error}");
        assert_eq!(resolve(&graphs, " ").unwrap_err(), "no file chosen");
        std::os::unix::fs::symlink(dir.join("secret.png"), graphs.join("link.png")).unwrap();
        let error = resolve(&graphs, "link.png").unwrap_err();
        assert!(error.contains("a link leads it out of"), "{error}");
        // A link to a folder the written path could reach by itself is followed.
        std::os::unix::fs::symlink(graphs.join("textures"), graphs.join("t")).unwrap();
        assert!(resolve(&graphs, "t/mask.png").is_ok());
    }

    #[test]
    fn relative_paths_climb_to_the_shared_folder() {
        let folder = Path::new("/work/project/graphs/texture");
        let target = Path::new("/work/project/assets/photos/wall.jpg");
        assert_eq!(
            relative_to(folder, target),
            Path::new("../../assets/photos/wall.jpg")
        );
        assert_eq!(
            relative_to(folder, Path::new("/work/project/graphs/texture/a.png")),
            Path::new("a.png")
        );
    }
}
