//! Probes: code lowered only to learn a type (`peek_type`, a `let o =
//! None;`'s type from its later uses), then undone. A [`Snapshot`] is the
//! lowerer's state a probe may change; [`FnLowerer::restore`] puts it
//! back, so that a field added to the lowerer is restored in this one
//! place.

use super::*;
use std::collections::BTreeMap;

/// What a probe may change of a [`FnLowerer`], as it was before.
pub(super) struct Snapshot {
    blocks: usize,
    scopes: usize,
    names: HashSet<String>,
    local_consts: HashSet<String>,
    pub(super) ivars: Vec<(u32, Option<Scalar>)>,
    loop_depth: u32,
    breaks: usize,
    loop_values: usize,
    writebacks: usize,
    intrinsics: usize,
    calls: usize,
    method_calls: usize,
    traced: usize,
    errors: usize,
    pending_tuples: usize,
    /// The expressions' types so far, taken out: the probe's go to a map
    /// of their own ([`FnLowerer::restore`] says which are kept).
    expr_types: std::collections::HashMap<usize, Ty>,
    /// The module's tuple and `Option` types: a probe's unknown `Option`s
    /// are not types.
    tuples: BTreeMap<String, Ty>,
}

impl FnLowerer<'_> {
    /// The state a probe may change, before it starts (with a block of
    /// its own to emit into, which [`FnLowerer::restore`] drops).
    pub(super) fn snapshot(&mut self) -> Snapshot {
        let s = Snapshot {
            blocks: self.blocks.len(),
            scopes: self.scopes.len(),
            names: self.names.clone(),
            local_consts: self.local_consts.clone(),
            ivars: self.ivars.clone(),
            loop_depth: self.loop_depth,
            breaks: self.breaks.len(),
            loop_values: self.loop_values.len(),
            writebacks: self.writebacks.len(),
            intrinsics: self.intrinsics.len(),
            calls: self.calls.len(),
            method_calls: self.method_calls.len(),
            traced: self.traced.len(),
            errors: self.errors.0.len(),
            pending_tuples: self.pending_tuples.len(),
            expr_types: std::mem::take(&mut self.expr_types),
            tuples: self.m.tuples.borrow().clone(),
        };
        self.blocks.push(Block::default());
        s
    }

    /// Puts back what `s` saved. The typed form keeps the types the probe
    /// gave its expressions where `keep_types`, but those naming the
    /// probe's own integer inference variables, which go with it.
    pub(super) fn restore(&mut self, s: Snapshot, keep_types: bool) {
        let probed = std::mem::replace(&mut self.expr_types, s.expr_types);
        if keep_types {
            let live = s.ivars.len();
            self.expr_types.extend(probed.into_iter().filter(|(_, t)| !names_ivar_from(t, live)));
        }
        self.blocks.truncate(s.blocks);
        self.scopes.truncate(s.scopes);
        self.names = s.names;
        self.local_consts = s.local_consts;
        self.ivars = s.ivars;
        self.loop_depth = s.loop_depth;
        self.breaks.truncate(s.breaks);
        self.loop_values.truncate(s.loop_values);
        self.writebacks.truncate(s.writebacks);
        self.intrinsics.truncate(s.intrinsics);
        self.calls.truncate(s.calls);
        self.method_calls.truncate(s.method_calls);
        self.traced.truncate(s.traced);
        self.errors.0.truncate(s.errors);
        self.pending_tuples.truncate(s.pending_tuples);
        *self.m.tuples.borrow_mut() = s.tuples;
    }
}

/// Whether `t` names an integer inference variable numbered `first` or
/// above.
fn names_ivar_from(t: &Ty, first: usize) -> bool {
    match t {
        Ty::IntVar(v) => *v as usize >= first,
        Ty::Array(e, _) | Ty::Ref(_, e) => names_ivar_from(e, first),
        Ty::Tuple(ts) => ts.iter().any(|t| names_ivar_from(t, first)),
        _ => false,
    }
}
