//! Long lists of messages made readable: identical lines folded into one with a count,
//! and at most [`MAX_LINES`] different lines, so that a hostile file (a million duplicate
//! wires) gets a summary instead of a million lines.

use std::borrow::Cow;
use std::collections::HashMap;

/// `count` and `noun`, plural but for exactly one: "1 node", "2 nodes", "0 nodes".
pub fn counted(count: usize, noun: &str) -> String {
    if count == 1 {
        format!("1 {noun}")
    } else {
        format!("{count} {noun}s")
    }
}

/// The most different lines a summary keeps; the rest are counted in its last line.
pub const MAX_LINES: usize = 100;

/// `lines` in their order of first appearance, each repeated line once followed by
/// `… and N more like this`, and past [`MAX_LINES`] different lines a final
/// `… and N more` (counting every line left out).
pub fn summarise(lines: impl IntoIterator<Item = String>) -> Vec<String> {
    let mut first: Vec<(String, usize)> = Vec::new();
    let mut seen: HashMap<String, usize> = HashMap::new();
    let mut left_out = 0usize;
    for line in lines {
        if let Some(&k) = seen.get(&line) {
            first[k].1 += 1;
        } else if first.len() < MAX_LINES {
            seen.insert(line.clone(), first.len());
            first.push((line, 1));
        } else {
            left_out += 1;
        }
    }
    let mut summary = Vec::with_capacity(first.len() * 2 + 1);
    for (line, count) in first {
        summary.push(line);
        if count > 1 {
            summary.push(format!("… and {} more like this", thousands(count - 1)));
        }
    }
    if left_out > 0 {
        summary.push(format!("… and {} more", thousands(left_out)));
    }
    summary
}

/// `n` with a comma every three digits: `1,000,000`.
pub fn thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut text = String::with_capacity(digits.len() + digits.len() / 3);
    for (k, digit) in digits.chars().enumerate() {
        if k > 0 && (digits.len() - k) % 3 == 0 {
            text.push(',');
        }
        text.push(digit);
    }
    text
}

/// `text` safe to print on a terminal: control characters other than line breaks and
/// tabs (ANSI and OSC escape sequences begin with one) and the C1 controls are written
/// as Rust escapes (`\u{1b}`), so a label or file name taken from a file cannot move
/// the cursor, recolour, retitle or clear the user's terminal. Text without them is
/// borrowed unchanged.
pub fn printable(text: &str) -> Cow<'_, str> {
    let unsafe_char = |c: char| c.is_control() && c != '\n' && c != '\t';
    if !text.contains(unsafe_char) {
        return Cow::Borrowed(text);
    }
    let mut escaped = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if unsafe_char(c) {
            escaped.extend(c.escape_unicode());
        } else {
            escaped.push(c);
        }
    }
    Cow::Owned(escaped)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thousands_are_separated() {
        assert_eq!(thousands(0), "0");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(1000), "1,000");
        assert_eq!(thousands(999_999), "999,999");
        assert_eq!(thousands(1_234_567), "1,234,567");
    }

    #[test]
    fn terminal_controls_are_escaped_and_text_kept() {
        assert!(matches!(printable("wood\tring 1\n"), Cow::Borrowed(_)));
        assert_eq!(
            printable("\u{1b}[2J\u{1b}]0;pwned\u{7}node\r\u{9b}31m é"),
            "\\u{1b}[2J\\u{1b}]0;pwned\\u{7}node\\u{d}\\u{9b}31m é"
        );
    }

    #[test]
    fn repeated_lines_fold_and_many_lines_are_counted() {
        let lines = ["a", "b", "a", "a"].map(String::from);
        assert_eq!(summarise(lines), ["a", "… and 2 more like this", "b"]);
        let many = (0..MAX_LINES + 5).map(|k| k.to_string());
        let summary = summarise(many);
        assert_eq!(summary.len(), MAX_LINES + 1);
        assert_eq!(summary.last().unwrap(), "… and 5 more");
    }
}
