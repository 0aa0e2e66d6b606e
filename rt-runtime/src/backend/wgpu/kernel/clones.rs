//! Per-depth clones: the megakernel's fallback for tracing programs that
//! have no resumable form. WGSL has no recursion, so everything that traces
//! is cloned per trace depth (`_d<k>`), each clone's traces calling the
//! next depth's; `clone_estimate` says what that costs before it is built.
//!
//! Which names a clone renames is a fact the compiler recorded while
//! lowering ([`WgslSite`]: a function's own name, its trace calls and its
//! helper calls, each with the byte offset where the name ends): the linker
//! inserts suffixes at those offsets and searches no text.

use super::*;
use rt_std::program::{ProgramDescriptor, TypeLayout, WgslItem, WgslName, WgslSite};
use std::collections::{BTreeMap, BTreeSet};

/// Linked types or shared functions by WGSL name, each with the program it
/// came from.
pub(super) type Linked = BTreeMap<&'static str, (&'static WgslItem, &'static ProgramDescriptor)>;

/// The helpers that trace: with a trace call site of their own, or calling
/// a helper that traces (a helper tracing only through another was emitted
/// once, calling a name only its per-depth clones had: the link failed).
pub(super) fn helpers_that_trace(functions: &Linked) -> BTreeSet<&'static str> {
    helpers_reaching(functions, |s| matches!(s, WgslName::Trace(_)))
}

/// The helpers with a site that `own` picks in their text, or calling a
/// helper that has one, however far down (helpers do not recurse: the
/// compiler rejects it, so this ends).
pub(super) fn helpers_reaching(functions: &Linked, own: impl Fn(&WgslName) -> bool) -> BTreeSet<&'static str> {
    let mut found: BTreeSet<&'static str> =
        functions.iter().filter(|(_, (f, _))| f.sites.iter().any(|s| own(&s.name))).map(|(n, _)| *n).collect();
    loop {
        let callers: Vec<&'static str> = functions
            .iter()
            .filter(|(n, (f, _))| {
                !found.contains(*n) && f.sites.iter().any(|s| matches!(s.name, WgslName::Call(h) if found.contains(h)))
            })
            .map(|(n, _)| *n)
            .collect();
        if callers.is_empty() {
            return found;
        }
        found.extend(callers);
    }
}

/// A function's text at depth `k`: its own name and its calls of tracing
/// helpers get `_d<k>`, its trace calls `_d<k+1>` (the next depth's trace
/// functions).
pub(super) fn at_depth(text: &str, sites: &[WgslSite], depth: u32, tracing_helpers: &BTreeSet<&str>) -> String {
    let mut out = String::with_capacity(text.len() + 4 * sites.len());
    let mut from = 0;
    for site in sites {
        let d = match site.name {
            WgslName::Definition => depth,
            WgslName::Trace(_) => depth + 1,
            WgslName::Call(h) if tracing_helpers.contains(h) => depth,
            WgslName::Call(_) | WgslName::Dispatch(_) => continue,
        };
        let end = site.end as usize;
        out.push_str(&text[from..end]);
        out.push_str(&format!("_d{d}"));
        from = end;
    }
    out.push_str(&text[from..]);
    out
}

/// Trace call sites of a function, counting those of the tracing helpers it
/// calls.
pub(super) fn trace_sites(sites: &[WgslSite], functions: &Linked, tracing: &BTreeSet<&str>) -> u64 {
    sites
        .iter()
        .map(|s| match s.name {
            WgslName::Trace(_) => 1,
            WgslName::Call(h) if tracing.contains(h) => {
                functions.get(h).map_or(0, |(f, _)| trace_sites(f.sites, functions, tracing))
            }
            WgslName::Call(_) | WgslName::Definition | WgslName::Dispatch(_) => 0,
        })
        .fold(0, u64::saturating_add)
}

/// How many copies of the traversal per-depth clones inline: the
/// ray-generation program's trace sites, times the sites of every
/// closest-hit and miss program at each further depth.
pub(super) fn clone_estimate(
    spec: &KernelSpec,
    all: &[KernelProgram],
    functions: &Linked,
    tracing: &BTreeSet<&str>,
) -> u64 {
    let rg = trace_sites(spec.ray_generation.desc.wgsl_program_sites, functions, tracing);
    let mut seen = BTreeSet::new();
    let per_level: u64 = all
        .iter()
        .filter(|p| {
            matches!(p.desc.kind, ProgramKind::ClosestHit | ProgramKind::Miss) && seen.insert(p.desc.wgsl_entry)
        })
        .map(|p| trace_sites(p.desc.wgsl_program_sites, functions, tracing))
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
    tracing_helpers: &BTreeSet<&str>,
) -> String {
    let mut out = String::new();
    // Programs: tracing kinds cloned per depth.
    out.push_str("\n// ---- programs ----\n");
    let mut emitted: BTreeSet<&str> = BTreeSet::new();
    for p in all {
        if !emitted.insert(p.desc.wgsl_entry) {
            continue;
        }
        let (text, sites) = (p.desc.wgsl_program, p.desc.wgsl_program_sites);
        match p.desc.kind {
            ProgramKind::RayGeneration => out.push_str(&at_depth(text, sites, 0, tracing_helpers)),
            ProgramKind::ClosestHit | ProgramKind::Miss => {
                for d in 1..=spec.max_depth {
                    out.push_str(&at_depth(text, sites, d, tracing_helpers));
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
            "fn rt_trace_{w}_d{}(object: u32, ray: RtRay, prd: ptr<function, {w}>, flags: u32, mask: u32) {{\n    rt_next_time = 0.0;\n    rt_raise(RT_EXC_TRACE_DEPTH);\n}}\n",
            spec.max_depth + 1
        ));
    }

    out
}
