//! Per-depth clones: the megakernel's fallback for tracing programs that
//! have no resumable form. WGSL has no recursion, so everything that traces
//! is cloned per trace depth (`_d<k>`), each clone's traces calling the
//! next depth's; `clone_estimate` says what that costs before it is built.

use super::*;
use rt_std::program::{ProgramDescriptor, TypeLayout};
use std::collections::{BTreeMap, BTreeSet};

/// Renames a function's tracing calls for depth `k`.
pub(super) fn at_depth(
    text: &str,
    depth: u32,
    tracing_helpers: &BTreeSet<String>,
    rename_self: Option<&str>,
) -> String {
    let mut out = text.to_string();
    if let Some(name) = rename_self {
        out = out.replacen(&format!("fn {name}("), &format!("fn {name}_d{depth}("), 1);
    }
    // rt_trace_<P>( → rt_trace_<P>_d<k+1>(
    let mut result = String::with_capacity(out.len());
    let mut rest = out.as_str();
    while let Some(i) = rest.find("rt_trace_") {
        result.push_str(&rest[..i]);
        let tail = &rest[i..];
        let end = tail.find('(').unwrap_or(tail.len());
        let ident = &tail[..end];
        if ident.chars().all(|c| c.is_alphanumeric() || c == '_') && end < tail.len() {
            result.push_str(&format!("{ident}_d{}", depth + 1));
        } else {
            result.push_str(ident);
        }
        rest = &tail[end..];
    }
    result.push_str(rest);
    for h in tracing_helpers {
        result = result.replace(&format!("{h}("), &format!("{h}_d{depth}("));
        // Undo the rename of the helper's own definition line when cloning
        // the helper itself (handled by `rename_self`).
        result = result.replace(&format!("fn {h}_d{depth}_d{depth}("), &format!("fn {h}_d{depth}("));
    }
    result
}

/// Trace call sites in a function's text, counting those of the tracing
/// helpers it calls.
pub(super) fn trace_sites(
    text: &str,
    functions: &BTreeMap<&str, (&str, &ProgramDescriptor)>,
    tracing: &BTreeSet<String>,
) -> u64 {
    let mut n = text.matches("rt_trace_").count() as u64;
    for h in tracing {
        let calls = text.matches(&format!("{h}(")).count().saturating_sub(text.matches(&format!("fn {h}(")).count());
        if calls > 0
            && let Some((body, _)) = functions.get(h.as_str())
        {
            n = n.saturating_add((calls as u64).saturating_mul(trace_sites(body, functions, tracing)));
        }
    }
    n
}

/// How many copies of the traversal per-depth clones inline: the
/// ray-generation program's trace sites, times the sites of every
/// closest-hit and miss program at each further depth.
pub(super) fn clone_estimate(
    spec: &KernelSpec,
    all: &[KernelProgram],
    functions: &BTreeMap<&str, (&str, &ProgramDescriptor)>,
    tracing: &BTreeSet<String>,
) -> u64 {
    let rg = trace_sites(spec.ray_generation.desc.wgsl_program, functions, tracing);
    let mut seen = BTreeSet::new();
    let per_level: u64 = all
        .iter()
        .filter(|p| {
            matches!(p.desc.kind, ProgramKind::ClosestHit | ProgramKind::Miss) && seen.insert(p.desc.wgsl_entry)
        })
        .map(|p| trace_sites(p.desc.wgsl_program, functions, tracing))
        .fold(0, u64::saturating_add);
    let (mut total, mut level) = (0u64, rg);
    for _ in 0..spec.max_depth {
        total = total.saturating_add(level);
        level = level.saturating_mul(per_level);
        if level == 0 {
            break;
        }
    }
    total
}

/// Programs and trace functions for kernels whose tracing programs are not
/// all resumable: everything that traces is cloned per depth (`_d<k>`).
pub(super) fn per_depth_clones(
    spec: &KernelSpec,
    all: &[KernelProgram],
    payloads: &BTreeMap<&str, TypeLayout>,
    payload_ids: &BTreeMap<&str, u32>,
    tracing_helpers: &BTreeSet<String>,
) -> String {
    let mut out = String::new();
    // Programs: tracing kinds cloned per depth.
    out.push_str("\n// ---- programs ----\n");
    let mut emitted: BTreeSet<&str> = BTreeSet::new();
    for p in all {
        if !emitted.insert(p.desc.wgsl_entry) {
            continue;
        }
        let text = p.desc.wgsl_program;
        match p.desc.kind {
            ProgramKind::RayGeneration => out.push_str(&at_depth(text, 0, tracing_helpers, Some(p.desc.wgsl_entry))),
            ProgramKind::ClosestHit | ProgramKind::Miss if traces(p.desc) || text.contains("rtf_") => {
                for d in 1..=spec.max_depth {
                    out.push_str(&at_depth(text, d, tracing_helpers, Some(p.desc.wgsl_entry)));
                }
            }
            ProgramKind::ClosestHit | ProgramKind::Miss => {
                for d in 1..=spec.max_depth {
                    out.push_str(&text.replacen(
                        &format!("fn {}(", p.desc.wgsl_entry),
                        &format!("fn {}_d{d}(", p.desc.wgsl_entry),
                        1,
                    ));
                }
            }
            _ => out.push_str(text),
        }
    }

    out.push_str("\n// ---- trace ----\n");
    for w in payloads.keys() {
        // Visit programs check the traced payload type against theirs.
        let note_payload =
            if spec.graph_levels > 0 { format!("\n    rt_s_payload = {}u;", payload_ids[w]) } else { String::new() };
        for d in 1..=spec.max_depth {
            out.push_str(&dispatch_payload(&spec.programs, w, d));
            out.push_str(&trace_function(w, d, &note_payload));
        }
        out.push_str(&format!(
            "fn rt_trace_{w}_d{}(object: u32, ray: RtRay, prd: ptr<function, {w}>, flags: u32, mask: u32) {{\n    rt_raise(RT_EXC_TRACE_DEPTH);\n}}\n",
            spec.max_depth + 1
        ));
    }

    out
}
