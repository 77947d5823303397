//! Writing to stdout and stderr without panicking: `println!` aborts the program when
//! the stream is full or closed. Here a reader that went away (a closed pipe, as in
//! `veneer mesh torus --json | head -c1`) ends the command quietly, and any other write
//! error (`> /dev/full`) is a failure with exit code 1. Text is written through
//! [`printable`], so control characters from a file's labels or names never reach the
//! terminal as escape sequences.

use super::Failure;
use std::fmt::Display;
use std::io::Write;
use veneer::messages::printable;

/// Writes `text` and a line break to stdout.
pub fn out(text: impl Display) -> Result<(), Failure> {
    let mut stdout = std::io::stdout().lock();
    writeln!(stdout, "{}", printable(&text.to_string()))
        .and_then(|()| stdout.flush())
        .map_err(|error| stream_failure(error, "stdout"))
}

/// Writes raw bytes to stdout.
pub fn out_bytes(bytes: &[u8]) -> Result<(), Failure> {
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(bytes)
        .and_then(|()| stdout.flush())
        .map_err(|error| stream_failure(error, "stdout"))
}

/// Writes `text` and a line break to stderr (warnings, summaries).
pub fn note(text: impl Display) -> Result<(), Failure> {
    writeln!(std::io::stderr().lock(), "{}", printable(&text.to_string()))
        .map_err(|error| stream_failure(error, "stderr"))
}

/// The failure for a write error on a standard stream: quiet when the reader is gone.
fn stream_failure(error: std::io::Error, stream: &str) -> Failure {
    if error.kind() == std::io::ErrorKind::BrokenPipe {
        Failure::reader_gone()
    } else {
        Failure::new(format!("cannot write to {stream}: {error}"))
    }
}

/// Prints a failure's message on stderr and gives its exit code: 1 at least when the
/// message could not be written, since the user never saw why the command stopped.
pub fn report_failure(Failure(message, code): Failure) -> u8 {
    if message.is_empty() {
        return code;
    }
    match writeln!(std::io::stderr().lock(), "{}", printable(&message)) {
        Ok(()) => code,
        Err(_) => code.max(1),
    }
}
