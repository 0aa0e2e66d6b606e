//! Callable programs in the megakernel: which callables a kernel links (those
//! of a signature some linked program calls, and so on through the
//! callables' own calls), and one dispatch function per signature,
//! `rt_call_<signature>(id, args..)`, a `switch` over the ids of the
//! callables of that signature whose default raises
//! `EXCEPTION_PROGRAM_ID_INVALID` and returns zero. WGSL has no recursion,
//! so callables that call each other in a cycle are a link error.

use super::KernelProgram;
use crate::error::{Result, RtError};
use rt_std::program::CallableSignature;
use std::collections::{BTreeMap, BTreeSet};

/// The signatures the kernel calls (by dispatch name) and the callables it
/// links, for the programs `all` out of the context's `callables`.
pub fn linked(
    all: &[KernelProgram],
    callables: &[KernelProgram],
) -> Result<(BTreeMap<&'static str, CallableSignature>, Vec<KernelProgram>)> {
    let mut called: BTreeMap<&'static str, CallableSignature> = BTreeMap::new();
    let mut todo: Vec<CallableSignature> = all.iter().flat_map(|p| p.desc.calls.iter().copied()).collect();
    while let Some(sig) = todo.pop() {
        if called.insert(sig.dispatch, sig).is_some() {
            continue;
        }
        for c in callables_of(callables, sig.dispatch) {
            todo.extend(c.desc.calls.iter().copied());
        }
    }
    let linked: Vec<KernelProgram> = callables
        .iter()
        .copied()
        .filter(|c| c.desc.callable.is_some_and(|s| called.contains_key(s.signature.dispatch)))
        .collect();
    check_acyclic(&linked)?;
    Ok((called, linked))
}

fn callables_of<'a>(callables: &'a [KernelProgram], dispatch: &'a str) -> impl Iterator<Item = &'a KernelProgram> {
    callables.iter().filter(move |c| c.desc.callable.is_some_and(|s| s.signature.dispatch == dispatch))
}

/// Callables calling back into their own signature, directly or through
/// others: the cycle, spelled out.
fn check_acyclic(linked: &[KernelProgram]) -> Result<()> {
    fn visit(
        c: &KernelProgram,
        linked: &[KernelProgram],
        path: &mut Vec<KernelProgram>,
        done: &mut BTreeSet<u32>,
    ) -> Result<()> {
        if let Some(at) = path.iter().position(|p| p.case == c.case) {
            let cycle: Vec<String> = path[at..]
                .iter()
                .chain(std::iter::once(c))
                .map(|p| format!("`{}` ({})", p.desc.name, p.desc.location()))
                .collect();
            return Err(RtError::CallableCycle { cycle: cycle.join(" calls ") });
        }
        if !done.insert(c.case) {
            return Ok(());
        }
        path.push(*c);
        for sig in c.desc.calls {
            for next in callables_of(linked, sig.dispatch) {
                visit(next, linked, path, done)?;
            }
        }
        path.pop();
        Ok(())
    }
    let mut done = BTreeSet::new();
    for c in linked {
        // A cycle through `c` is found from `c`, whatever was visited.
        done.clear();
        visit(c, linked, &mut Vec::new(), &mut done)?;
    }
    Ok(())
}

/// The dispatch functions of `called` over the `linked` callables.
pub fn dispatch(called: &BTreeMap<&'static str, CallableSignature>, linked: &[KernelProgram]) -> String {
    let mut out = String::new();
    for (name, sig) in called {
        let params: String = sig.params.iter().enumerate().map(|(i, t)| format!(", a{i}: {t}")).collect();
        let args: Vec<String> = (0..sig.params.len()).map(|i| format!("a{i}")).collect();
        let args = args.join(", ");
        let mut cases = String::new();
        for c in callables_of(linked, name) {
            let f = c.desc.wgsl_entry;
            let call = match sig.ret {
                Some(_) => format!("return {f}({args});"),
                None => format!("{f}({args});"),
            };
            cases.push_str(&format!("        case {}u: {{ {call} }}\n", c.case));
        }
        let (ret, tail) = match sig.ret {
            Some(r) => (format!(" -> {r}"), format!("    var r: {r};\n    return r;\n")),
            None => (String::new(), String::new()),
        };
        out.push_str(&format!(
            "fn {name}(id: u32{params}){ret} {{\n    switch id {{\n{cases}        default: {{ rt_raise(RT_EXC_PROGRAM_ID); }}\n    }}\n{tail}}}\n"
        ));
    }
    out
}
