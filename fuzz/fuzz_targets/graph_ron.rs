//! The RON graph loader on arbitrary text: it loads or says why, never panics; whatever
//! loads saves to text that loads back to the same text; and what loaded goes through
//! the check, codegen and naga without a panic or a naga error after the check passed.

#![no_main]

use libfuzzer_sys::fuzz_target;
use veneer::codegen::{CompileError, compile};
use veneer::graph::{from_ron, to_ron};

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    let graph = match from_ron(text) {
        Ok(graph) => graph,
        Err(error) => {
            assert!(
                error.position.is_some(),
                "a load error without a position: {error}"
            );
            return;
        }
    };
    let saved = to_ron(&graph);
    let reloaded = from_ron(&saved).unwrap_or_else(|error| panic!("{error}\n{saved}"));
    assert_eq!(
        to_ron(&reloaded),
        saved,
        "save → load → save changed the text"
    );
    if let Err(CompileError::Validation(error)) = compile(&graph, &Default::default()) {
        panic!("naga rejected a checked graph: {error}\n{saved}");
    }
});
