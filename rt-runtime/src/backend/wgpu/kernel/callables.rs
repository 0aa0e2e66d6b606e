//! Callable programs in the megakernel: one dispatch function per
//! signature, `rt_call_<signature>(id, args..)`, a `switch` over the ids of
//! the linked callables of that signature whose default raises
//! `EXCEPTION_PROGRAM_ID_INVALID` and returns zero. A callable's `#[var]`
//! variables come from its record, which the scene's table at header word 3
//! locates by program index (`encode`). Which callables a kernel
//! links (those of a signature some linked program calls, and so on through
//! the callables' own calls) and the refusal of cycles (WGSL has no
//! recursion) are the link's, the same for every backend
//! (`crate::link::callables`).
//!
//! A callable that calls through ids calls dispatch functions of its own,
//! `rt_call_<signature>_from_<callable>`, whose `switch` leaves the callable
//! itself out (its id raises, as on the CPU backend): so a callable may call
//! callables of its own signature and the module still has no recursion.
//! The calls it renames, in its text and in the helpers it calls that
//! dispatch (each cloned under the same suffix), are the sites the compiler
//! recorded (`WgslName::Dispatch`, `WgslName::Call`); no text is searched.

use super::clones::{Linked, helpers_reaching};
use crate::link::callables::{LinkedCallable, callable_from, of_signature};
use rt_std::program::{CallableSignature, WgslName, WgslSite};
use std::collections::{BTreeMap, BTreeSet};

/// The dispatch functions of `called` over the `linked` callables, which
/// the programs that are not callables call.
pub fn dispatch(called: &BTreeMap<&'static str, CallableSignature>, linked: &[LinkedCallable]) -> String {
    let mut out = String::new();
    for (name, sig) in called {
        out.push_str(&dispatcher(name, sig, of_signature(linked, name)));
    }
    out
}

/// The `linked` callables' functions, each once, and for those that call
/// through ids their own dispatch functions and their clones of the
/// helpers that dispatch (`functions`: the kernel's shared functions).
pub fn callable_functions(
    called: &BTreeMap<&'static str, CallableSignature>,
    linked: &[LinkedCallable],
    functions: &Linked,
) -> String {
    let dispatching = helpers_reaching(functions, |s| matches!(s, WgslName::Dispatch(_)));
    let mut out = String::new();
    // The same callable created twice: two ids, one function.
    let mut emitted: BTreeSet<&str> = BTreeSet::new();
    for c in linked.iter().filter(|c| emitted.insert(c.desc.wgsl_entry)) {
        let desc = c.desc;
        if desc.calls.is_empty() {
            out.push_str(desc.wgsl_program);
            continue;
        }
        let suffix = format!("_from_{}", desc.wgsl_entry);
        out.push_str(&renamed(desc.wgsl_program, desc.wgsl_program_sites, &suffix, &dispatching, false));
        for h in helpers_called(desc.wgsl_program_sites, functions, &dispatching) {
            let (item, _) = functions[h];
            out.push_str(&renamed(item.text, item.sites, &suffix, &dispatching, true));
        }
        let mut signatures: BTreeSet<&str> = BTreeSet::new();
        for sig in desc.calls.iter().filter(|s| signatures.insert(s.dispatch)) {
            let sig = called.get(sig.dispatch).unwrap_or(sig);
            let name = format!("{}{suffix}", sig.dispatch);
            out.push_str(&dispatcher(&name, sig, callable_from(desc, linked, sig.dispatch)));
        }
    }
    out
}

/// The helpers among `dispatching` that `sites` call, however far down,
/// each once, in name order.
fn helpers_called(sites: &[WgslSite], functions: &Linked, dispatching: &BTreeSet<&'static str>) -> Vec<&'static str> {
    let mut found: BTreeSet<&'static str> = BTreeSet::new();
    let mut todo: Vec<&'static str> = WgslSite::helpers_called(sites);
    while let Some(h) = todo.pop() {
        if dispatching.contains(h)
            && found.insert(h)
            && let Some((item, _)) = functions.get(h)
        {
            todo.extend(WgslSite::helpers_called(item.sites));
        }
    }
    found.into_iter().collect()
}

/// `text` with `suffix` after its dispatch calls and its calls of the
/// `dispatching` helpers, and after its own name when `own`.
fn renamed(text: &str, sites: &[WgslSite], suffix: &str, dispatching: &BTreeSet<&str>, own: bool) -> String {
    let mut out = String::with_capacity(text.len() + suffix.len() * sites.len());
    let mut from = 0;
    for site in sites {
        let rename = match site.name {
            WgslName::Definition => own,
            WgslName::Dispatch(_) => true,
            WgslName::Call(h) => dispatching.contains(h),
            WgslName::Trace(_) => false,
        };
        if rename {
            let end = site.end as usize;
            out.push_str(&text[from..end]);
            out.push_str(suffix);
            from = end;
        }
    }
    out.push_str(&text[from..]);
    out
}

/// The dispatch function `name` of signature `sig`: a `switch` over the
/// ids of `cases`, whose default raises and returns zero.
fn dispatcher<'a>(name: &str, sig: &CallableSignature, cases: impl Iterator<Item = &'a LinkedCallable>) -> String {
    let params: String = sig.params.iter().enumerate().map(|(i, t)| format!(", a{i}: {t}")).collect();
    let mut arms = String::new();
    for c in cases {
        let f = c.desc.wgsl_entry;
        // Variables first (the compiler's parameter order), from the
        // callable's record in the scene's table by program index.
        let mut all = super::var_args(c.desc, "v");
        all.extend((0..sig.params.len()).map(|i| format!("a{i}")));
        let all = all.join(", ");
        let record = match crate::scene::ProgramId::from_callable_id(c.id) {
            Some(p) if !c.desc.variables.is_empty() => format!("let v = rt_scene[rt_scene[3] + {}u]; ", p.index()),
            _ => String::new(),
        };
        let call = match sig.ret {
            Some(_) => format!("return {f}({all});"),
            None => format!("{f}({all});"),
        };
        arms.push_str(&format!("        case {}u: {{ {record}{call} }}\n", c.id));
    }
    let (ret, tail) = match sig.ret {
        Some(r) => (format!(" -> {r}"), format!("    var r: {r};\n    return r;\n")),
        None => (String::new(), String::new()),
    };
    format!(
        "fn {name}(id: u32{params}){ret} {{\n    switch id {{\n{arms}        default: {{ rt_raise(RT_EXC_PROGRAM_ID); }}\n    }}\n{tail}}}\n"
    )
}
