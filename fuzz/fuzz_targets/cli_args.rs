//! The command-line parser on arbitrary argument vectors (`veneer` followed by any
//! strings): a parsed command line or a usage error with exit code 0 (help, version), 1,
//! or 2 (snapshot), never a panic; clap's own consistency checks run too, since fuzz
//! builds keep debug assertions. Running the parsed commands is the CLI contract suite's
//! job (`tests/engine/cli_contract.rs`), which starts the real binary.

#![no_main]

use libfuzzer_sys::fuzz_target;
use std::ffi::OsString;

// The binary's own parser: the CLI lives in the binary crate, not in the library.
#[allow(dead_code, unexpected_cfgs)]
#[path = "../../src/cli/mod.rs"]
mod cli;

fuzz_target!(|words: Vec<String>| {
    let args: Vec<OsString> = std::iter::once("veneer".to_string())
        .chain(words)
        .map(OsString::from)
        .collect();
    if let Err(error) = cli::parse_from(&args) {
        let code = cli::usage_exit_code(&args, &error);
        assert!(code <= 2);
        let _ = error.render().to_string();
    }
});
