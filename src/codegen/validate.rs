//! naga validation of generated WGSL.

use crate::graph::NodeId;
use std::fmt;

/// WGSL that naga rejected, with the node the offending code came from when known.
#[derive(Clone, Debug)]
pub struct ValidationError {
    pub message: String,
    /// Byte offset of the first labelled span.
    pub offset: Option<usize>,
    pub node: Option<NodeId>,
    pub node_name: Option<String>,
}

impl fmt::Display for ValidationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.node_name {
            Some(name) => write!(f, "{name}: generated WGSL is invalid: {}", self.message),
            None => write!(f, "generated WGSL is invalid: {}", self.message),
        }
    }
}

impl std::error::Error for ValidationError {}

/// Parses and validates a WGSL module with naga.
pub fn validate(source: &str) -> Result<naga::Module, ValidationError> {
    let module = naga::front::wgsl::parse_str(source).map_err(|error| {
        let offset = error
            .labels()
            .find_map(|(span, _)| span.to_range())
            .map(|range| range.start);
        let labels: Vec<String> = error
            .labels()
            .map(|(_, label)| label.to_string())
            .filter(|l| !l.is_empty())
            .collect();
        let message = if labels.is_empty() {
            error.message().to_string()
        } else {
            format!("{} ({})", error.message(), labels.join("; "))
        };
        ValidationError {
            message,
            offset,
            node: None,
            node_name: None,
        }
    })?;
    let mut validator = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    );
    validator.validate(&module).map_err(|error| {
        let offset = error
            .spans()
            .find_map(|(span, _)| span.to_range())
            .map(|range| range.start);
        let mut message = error.as_inner().to_string();
        let mut source_error = std::error::Error::source(error.as_inner());
        while let Some(cause) = source_error {
            message.push_str(": ");
            message.push_str(&cause.to_string());
            source_error = cause.source();
        }
        ValidationError {
            message,
            offset,
            node: None,
            node_name: None,
        }
    })?;
    Ok(module)
}
