//! What lowering an expression gives: a [`Val`] (WGSL text and its type),
//! and a [`Place`] an assignment writes to.

use crate::types::{BufferKind, Ty};

/// A lowered expression: WGSL text and its type.
#[derive(Clone, Debug)]
pub struct Val {
    pub code: String,
    pub ty: Ty,
}

impl Val {
    pub fn new(code: impl Into<String>, ty: Ty) -> Val {
        Val { code: code.into(), ty }
    }
}

/// Something that can be assigned to.
pub enum Place {
    Wgsl(String, Ty),
    /// An element of a buffer, with an optional member path into it.
    Buffer {
        buf: Val,
        kind: BufferKind,
        elem: Ty,
        index: String,
        path: String,
        ty: Ty,
    },
}

/// An f32 literal in WGSL: the shortest text that round-trips, with `f`.
pub fn f32_literal(v: f32) -> String {
    if v.is_nan() {
        return "bitcast<f32>(0x7fc00000u)".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "bitcast<f32>(0x7f800000u)".into() } else { "bitcast<f32>(0xff800000u)".into() };
    }
    let s = format!("{v:?}");
    format!("{s}f")
}
