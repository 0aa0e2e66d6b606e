//! What lowering an expression gives: a [`Val`] (WGSL text and its type),
//! and a [`Place`] an assignment writes to.

use crate::types::{BufferKind, Ty};

/// A lowered expression: WGSL text and its type.
#[derive(Clone, Debug)]
pub struct Val {
    pub code: String,
    pub ty: Ty,
    /// Evaluating `code` may have side effects: it calls a helper (which
    /// may write through `&mut` parameters or to buffers) or an intrinsic
    /// that reports an intersection. Set where such a call is lowered and
    /// carried into every value whose code contains it.
    pub effects: bool,
    /// `code` reads state that statements can change: a `var` local, a
    /// pointer parameter or a buffer element. Set where such a name or
    /// load is lowered and carried like `effects`.
    pub reads: bool,
}

impl Val {
    /// A value without effects.
    pub fn new(code: impl Into<String>, ty: Ty) -> Val {
        Val { code: code.into(), ty, effects: false, reads: false }
    }

    /// The value with its `effects` recorded.
    pub fn with_effects(mut self, effects: bool) -> Val {
        self.effects = effects;
        self
    }

    /// The value with `reads` recorded.
    pub fn with_reads(mut self, reads: bool) -> Val {
        self.reads = reads;
        self
    }
}

/// The code of each value.
pub fn codes(vals: &[Val]) -> Vec<String> {
    vals.iter().map(|v| v.code.clone()).collect()
}

/// Whether any of the values has effects.
pub fn any_effects(vals: &[Val]) -> bool {
    vals.iter().any(|v| v.effects)
}

/// Whether any of the values reads state.
pub fn any_reads(vals: &[Val]) -> bool {
    vals.iter().any(|v| v.reads)
}

/// Something that can be assigned to.
pub enum Place {
    /// A WGSL reference expression (with effects where an index has them).
    Wgsl(Val),
    /// An element of a buffer, with an optional member path into it.
    Buffer {
        buf: Val,
        kind: BufferKind,
        elem: Ty,
        index: String,
        path: String,
        ty: Ty,
        /// An index in `path` has effects.
        effects: bool,
    },
}

/// An f32 in WGSL (rt-abi's `f32_wgsl`: the shortest text that round-trips,
/// with `f`; infinity and NaN as a run-time call, never a constant).
pub fn f32_literal(v: f32) -> String {
    rt_abi::wgsl::f32_wgsl(v)
}
