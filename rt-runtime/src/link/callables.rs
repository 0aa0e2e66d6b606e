//! Callable programs at link time, for every backend: which callables a
//! launch links (those of a signature some linked program calls, and so on
//! through the callables' own calls), and the refusal of callables that
//! call each other in a cycle. WGSL has no recursion, so the wgpu kernel
//! cannot run a cycle; the CPU backend refuses it too, with the same error,
//! so that a scene runs on both or on neither (and a CPU launch never
//! recurses until its stack overflows).
//!
//! A callable may call callables of its own signature ("blend two
//! BRDFs"): every callable that calls through ids has dispatch functions of
//! its own, over the callables of each signature it calls except itself
//! ([`calls_itself`]). So only a cycle through two or more programs is
//! refused at link; a callable called through an id of its own program, by
//! itself, raises `EXCEPTION_PROGRAM_ID_INVALID` and returns zero, as an id
//! of no callable does, on every backend.

use crate::error::{LinkError, Result};
use crate::scene::{ProgramId, Scene};
use rt_std::program::{CallableSignature, ProgramDescriptor};
use std::collections::{BTreeMap, BTreeSet};

/// A callable program as a launch links it: the id programs call it
/// through and its descriptor.
#[derive(Clone, Copy)]
pub struct LinkedCallable {
    pub id: u32,
    pub desc: &'static ProgramDescriptor,
}

/// The context's callable programs, by id.
pub fn scene_callables(scene: &Scene) -> Vec<LinkedCallable> {
    scene
        .programs
        .iter()
        .enumerate()
        .filter(|(_, r)| r.desc.callable.is_some())
        .map(|(i, r)| LinkedCallable { id: ProgramId(i as u32).callable_id(), desc: r.desc })
        .collect()
}

/// The signatures the `callers` call (by dispatch name), directly or
/// through callables, and the `callables` linked for them; an error if
/// linked callables call each other in a cycle.
pub fn linked<'a>(
    callers: impl IntoIterator<Item = &'a ProgramDescriptor>,
    callables: &[LinkedCallable],
) -> Result<(BTreeMap<&'static str, CallableSignature>, Vec<LinkedCallable>)> {
    let mut called: BTreeMap<&'static str, CallableSignature> = BTreeMap::new();
    let mut todo: Vec<CallableSignature> = callers.into_iter().flat_map(|p| p.calls.iter().copied()).collect();
    while let Some(sig) = todo.pop() {
        if called.insert(sig.dispatch, sig).is_some() {
            continue;
        }
        for c in of_signature(callables, sig.dispatch) {
            todo.extend(c.desc.calls.iter().copied());
        }
    }
    let linked: Vec<LinkedCallable> = callables
        .iter()
        .copied()
        .filter(|c| c.desc.callable.is_some_and(|s| called.contains_key(s.signature.dispatch)))
        .collect();
    check_acyclic(&linked)?;
    Ok((called, linked))
}

/// The programs of the `linked` callables that read `#[var]` variables:
/// each has a record of its own (its scope, then the context's) on every
/// backend.
pub fn with_variables(linked: &[LinkedCallable]) -> impl Iterator<Item = ProgramId> + '_ {
    linked.iter().filter(|c| !c.desc.variables.is_empty()).filter_map(|c| ProgramId::from_callable_id(c.id))
}

/// The `callables` of the signature whose dispatch name is `dispatch`.
pub fn of_signature<'a>(
    callables: &'a [LinkedCallable],
    dispatch: &'a str,
) -> impl Iterator<Item = &'a LinkedCallable> {
    callables.iter().filter(move |c| c.desc.callable.is_some_and(|s| s.signature.dispatch == dispatch))
}

/// Whether a call from callable `caller` to `callee` would be the caller
/// calling itself (the same program, through any of its ids): no backend
/// makes that call (WGSL has no recursion); it raises
/// `EXCEPTION_PROGRAM_ID_INVALID` and returns zero instead.
pub fn calls_itself(caller: &ProgramDescriptor, callee: &ProgramDescriptor) -> bool {
    caller.wgsl_entry == callee.wgsl_entry
}

/// The `linked` callables of the signature whose dispatch name is
/// `dispatch` that callable `caller` may call (itself excepted).
pub fn callable_from<'a>(
    caller: &'a ProgramDescriptor,
    linked: &'a [LinkedCallable],
    dispatch: &'a str,
) -> impl Iterator<Item = &'a LinkedCallable> {
    of_signature(linked, dispatch).filter(move |c| !calls_itself(caller, c.desc))
}

/// Callables calling back into themselves through other programs: the
/// cycle, spelled out.
fn check_acyclic(linked: &[LinkedCallable]) -> Result<()> {
    fn visit(
        c: &LinkedCallable,
        linked: &[LinkedCallable],
        path: &mut Vec<LinkedCallable>,
        done: &mut BTreeSet<&'static str>,
    ) -> Result<()> {
        if let Some(at) = path.iter().position(|p| calls_itself(p.desc, c.desc)) {
            let cycle: Vec<String> = path[at..]
                .iter()
                .chain(std::iter::once(c))
                .map(|p| format!("`{}` ({})", p.desc.name, p.desc.location()))
                .collect();
            return Err(LinkError::CallableCycle { cycle: cycle.join(" calls ") }.into());
        }
        if !done.insert(c.desc.wgsl_entry) {
            return Ok(());
        }
        path.push(*c);
        for sig in c.desc.calls {
            for next in callable_from(c.desc, linked, sig.dispatch) {
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
