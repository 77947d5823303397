//! Names from a graph file that become parts of file names: a group's name names its
//! library file (`<name>.ron`), a parameter preset's names a golden image
//! (`<graph>.<preset>.png`). One rule for all of them, so that no name reaches a path
//! outside the folder it is joined to.

/// The most characters of a name that becomes part of a file name.
pub const MAX_NAME_CHARS: usize = 64;

/// Whether `name` may become part of a file name: 1 to [`MAX_NAME_CHARS`] letters,
/// digits (of any script), spaces and `_ - . ( ) +`, neither starting with `.`, `-` or
/// a space nor ending with `.` or a space. No separator, no `..`, no control character.
/// The error says what is wrong, `what` naming the name (`preset`, `group`).
pub fn file_name_part(what: &str, name: &str) -> Result<(), String> {
    let allowed = |c: char| c.is_alphanumeric() || " _-.()+".contains(c);
    let problem = if name.is_empty() {
        Some("is empty".to_string())
    } else if name.chars().count() > MAX_NAME_CHARS {
        Some(format!(
            "is {} characters long (at most {MAX_NAME_CHARS})",
            crate::messages::thousands(name.chars().count())
        ))
    } else if name.starts_with(['.', '-', ' ']) || name.ends_with(['.', ' ']) {
        Some("starts with '.', '-' or a space, or ends with '.' or a space".to_string())
    } else if !name.chars().all(allowed) {
        Some("has characters other than letters, digits, spaces and _ - . ( ) +".to_string())
    } else {
        None
    };
    match problem {
        None => Ok(()),
        Some(problem) => Err(format!(
            "{what} name '{}' {problem}: it becomes part of a file name",
            shown(name)
        )),
    }
}

/// `name` for a message: its first [`MAX_NAME_CHARS`] characters (control characters
/// escaped), `…` where it was cut.
pub fn shown(name: &str) -> String {
    let (start, cut) = super::clip(name, MAX_NAME_CHARS);
    let escaped: String = start.chars().flat_map(char::escape_debug).collect();
    format!("{escaped}{}", if cut { "…" } else { "" })
}

/// Group names as a path, `'a' › 'b' › 'c'`, the middle of a long one left out.
pub fn chain(names: &[&str]) -> String {
    let quoted = names.iter().map(|name| format!("'{}'", shown(name)));
    elided(quoted.collect(), " › ")
}

/// `items` joined by `separator`; past nine, only the first and last four, with how
/// many were left out between them.
pub fn elided(items: Vec<String>, separator: &str) -> String {
    const ENDS: usize = 4;
    if items.len() <= 2 * ENDS + 1 {
        return items.join(separator);
    }
    let skipped = format!(
        "… {} more …",
        crate::messages::thousands(items.len() - 2 * ENDS)
    );
    let mut kept: Vec<String> = items[..ENDS].to_vec();
    kept.push(skipped);
    kept.extend_from_slice(&items[items.len() - ENDS..]);
    kept.join(separator)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_that_could_leave_a_folder_are_refused() {
        for good in [
            "ring_wood",
            "oak",
            "veined marble",
            "Eiche (hell)",
            "v1.2",
            "x+y",
        ] {
            assert_eq!(file_name_part("group", good), Ok(()), "{good}");
        }
        for bad in [
            "",
            "x/../../escape",
            "../victim/libevil",
            "..",
            ".hidden",
            "-rf",
            "a\\b",
            "tab\there",
            "trailing.",
            "nul\0",
        ] {
            let error = file_name_part("preset", bad).expect_err(bad);
            assert!(error.starts_with("preset name '"), "{error}");
        }
        let long = "x".repeat(1_000_000);
        let error = file_name_part("group", &long).expect_err("long");
        assert!(error.contains("1,000,000 characters long"), "{error}");
        assert!(error.len() < 300, "{} bytes", error.len());
    }
}
