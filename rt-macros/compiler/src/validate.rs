//! naga validation of a lowered module, with naga's errors mapped back to
//! the Rust expression that produced the offending WGSL (via the source map
//! `lower::text` builds).

use crate::error::{Error, Errors};
use proc_macro2::Span;
use std::ops::Range;

/// Parses and validates `wgsl`; on failure returns errors at the Rust spans
/// of the innermost mapped range covering naga's span (or `fallback`).
pub fn validate(wgsl: &str, map: &[(Range<usize>, Span)], fallback: Span) -> Result<naga::Module, Errors> {
    let locate = |r: Option<Range<usize>>| -> Span {
        let Some(r) = r else { return fallback };
        map.iter()
            .filter(|(m, _)| m.start <= r.start && r.end <= m.end.max(r.start + 1))
            .min_by_key(|(m, _)| m.len())
            .map(|(_, s)| *s)
            .unwrap_or(fallback)
    };
    let module = match naga::front::wgsl::parse_str(wgsl) {
        Ok(m) => m,
        Err(e) => {
            let span = locate(e.labels().next().and_then(|(s, _)| s.to_range()));
            let labels: Vec<String> = e.labels().map(|(_, l)| l.to_string()).filter(|l| !l.is_empty()).collect();
            let detail = if labels.is_empty() { String::new() } else { format!(" ({})", labels.join("; ")) };
            return Err(Error::new(span, format!("generated WGSL does not parse: {}{detail}", e.message())).into());
        }
    };
    let mut validator =
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::default());
    if let Err(e) = validator.validate(&module) {
        let range = e.spans().filter_map(|(s, _)| s.to_range()).min_by_key(|r| r.len());
        let span = locate(range);
        let mut msg = e.as_inner().to_string();
        let mut src: Option<&dyn std::error::Error> = std::error::Error::source(e.as_inner());
        while let Some(s) = src {
            msg.push_str(": ");
            msg.push_str(&s.to_string());
            src = s.source();
        }
        return Err(Error::new(span, format!("naga rejects the WGSL lowered from this expression: {msg}")).into());
    }
    Ok(module)
}
