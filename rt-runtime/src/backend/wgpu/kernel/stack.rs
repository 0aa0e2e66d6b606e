//! The trace stack of kernels whose tracing programs are all resumable:
//! one frame per trace depth and the loop that runs the program on top.
//! Its fixed WGSL is in `stack_state.wgsl`, `stack_payload.wgsl` (per
//! payload type) and `stack_loop.wgsl`, templates whose `{name}`s this
//! file fills.

use super::switch_arms::Arms;
use super::{KernelProgram, KernelSpec, traces, var_args};
use rt_std::program::ProgramKind;
use std::collections::{BTreeMap, BTreeSet};

const STACK_STATE: &str = include_str!("stack_state.wgsl");
const STACK_PAYLOAD: &str = include_str!("stack_payload.wgsl");
const STACK_LOOP: &str = include_str!("stack_loop.wgsl");

/// Programs and the trace loop for kernels whose tracing programs are all
/// resumable (see rt-compiler's `func/resume.rs`): `rt_run` keeps a stack
/// of program invocations, one per trace depth (`rt_st_*[d]`), and runs the
/// top one with `rt_step` until it returns. A program that returns with
/// `rt_rs != 0` asked for a trace (the request is in `rt_rq_*`, its site in
/// its frame): the traversal runs at the one call site in
/// `rt_begin_trace`, and the hit's closest-hit or miss program becomes the
/// new top; when a program at depth `d > 0` finishes, its payload goes back
/// in the request slot and the caller is called again with `rt_rs = 1u`
/// to resume. Every program and the traversal appear once
/// in the kernel, whatever the maximum depth.
pub(super) fn stack_machine(spec: &KernelSpec, all: &[KernelProgram], payload_ids: &BTreeMap<&str, u32>) -> String {
    let mut out = String::from("\n// ---- trace stack ----\n");
    out.push_str(&fill(STACK_STATE, &[("depths", &(spec.max_depth + 1).to_string())]));
    let mut take_request = String::new();
    let mut after_search = String::new();
    let mut deliver = String::new();
    for (w, id) in payload_ids {
        out.push_str(&fill(STACK_PAYLOAD, &[("w", w), ("id", &id.to_string())]));
        take_request.push_str(&format!("        case {id}u: {{\n            rt_prd_{w} = rt_rq_{w};\n        }}\n"));
        after_search.push_str(&format!(
            "        case {id}u: {{\n            rt_rq_{w} = rt_prd_{w};\n            rt_pl_{w}[e] = rt_prd_{w};\n        }}\n"
        ));
        deliver.push_str(&format!("        case {id}u: {{\n            rt_rq_{w} = rt_pl_{w}[d];\n        }}\n"));
    }
    let mut ch_attrs: BTreeSet<&str> = BTreeSet::new();
    for p in all.iter().filter(|p| p.desc.kind == ProgramKind::ClosestHit) {
        if let Some(a) = p.desc.attributes {
            ch_attrs.insert(a.wgsl);
        }
    }
    for a in &ch_attrs {
        out.push_str(&format!("var<private> rt_at_{a}: array<{a}, RT_DEPTHS>;\n"));
    }

    // Resumable helpers and programs, once each.
    out.push_str("\n// ---- resumable helpers ----\n");
    let mut helpers: BTreeMap<&str, &str> = BTreeMap::new();
    for p in all.iter().filter(|p| traces(p.desc)) {
        for f in p.desc.wgsl_resumable_functions {
            helpers.entry(f.name).or_insert(f.text);
        }
    }
    for text in helpers.values() {
        out.push_str(text);
    }
    out.push_str("\n// ---- programs ----\n");
    let mut emitted: BTreeSet<&str> = BTreeSet::new();
    let mut cases = Arms::default();
    for p in all {
        // The same program created twice has two cases and one function.
        if emitted.insert(p.desc.wgsl_entry) {
            out.push_str(match p.desc.wgsl_resumable {
                Some(r) if traces(p.desc) => r,
                _ => p.desc.wgsl_program,
            });
        }
        let call = |args: Vec<String>| format!("{}({});", p.desc.wgsl_entry, args.join(", "));
        match p.desc.kind {
            ProgramKind::RayGeneration => {
                cases.add(p.case, format!("            {}\n", call(var_args(p.desc, "vars"))));
            }
            ProgramKind::ClosestHit | ProgramKind::Miss => {
                let Some(pl) = p.desc.payload else { continue };
                let w = pl.wgsl;
                let mut args = vec!["&p".to_string()];
                let mut attr = String::new();
                if let Some(a) = p.desc.attributes
                    && p.desc.kind == ProgramKind::ClosestHit
                {
                    attr = format!(
                        "            if rt_rs == 0u {{\n                rt_at_{0}[d] = rt_hit_attr_{0}();\n            }}\n",
                        a.wgsl
                    );
                    args.push(format!("rt_at_{}[d]", a.wgsl));
                }
                args.extend(var_args(p.desc, "vars"));
                cases.add(
                    p.case,
                    format!(
                        "            if rt_st_type[d] != {}u {{
                rt_raise(RT_EXC_INVALID_RAY);
                return;
            }}
{attr}            var p = rt_pl_{w}[d];
            {}
            rt_pl_{w}[d] = p;
",
                        payload_ids[w],
                        call(args)
                    ),
                );
            }
            _ => {}
        }
    }

    let note_payload = if spec.graph_levels > 0 { "\n    rt_s_payload = ty;" } else { "" };
    let cases = cases.render();
    out.push_str(&fill(
        STACK_LOOP,
        &[
            ("cases", &cases),
            ("take_request", &take_request),
            ("after_search", &after_search),
            ("deliver", &deliver),
            ("note_payload", note_payload),
            ("rg_case", &spec.ray_generation.case.to_string()),
        ],
    ));
    out
}

/// `template` with each `{name}` of `values` replaced by its value, in one
/// pass (a value's own braces are never read as names), and without the
/// comment lines that open the template (they describe the file, not the
/// kernel).
fn fill(template: &str, values: &[(&str, &str)]) -> String {
    let mut rest = template;
    while rest.starts_with("//") {
        rest = rest.split_once('\n').map_or("", |(_, after)| after);
    }
    let mut out = String::with_capacity(rest.len());
    while let Some(open) = rest.find('{') {
        out.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        let named = after.find('}').and_then(|close| {
            let name = &after[..close];
            values.iter().find(|(n, _)| *n == name).map(|(_, v)| (*v, close))
        });
        match named {
            Some((value, close)) => {
                out.push_str(value);
                rest = &after[close + 1..];
            }
            None => {
                out.push('{');
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}
