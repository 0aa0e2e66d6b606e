//! Lowers one Rust function body to WGSL, checking the subset's rules and
//! inferring types as it goes (one pass: every expression is typed when it
//! is lowered; unsuffixed integer literals get an inference variable that
//! later uses resolve, `i32` by default as in Rust).
//!
//! [`FnLowerer`] is one struct; its methods live by concern, one file each:
//! - `stmt`: statements, `let`, `const` items, `rt_printf!`;
//! - `expr`: the expression dispatch, literals, paths, fields, indexing,
//!   struct and array literals;
//! - `ops`: operators and casts;
//! - `eval`: evaluation order (spilling operands) and WGSL's constant
//!   expressions;
//! - `places`: assignment and `&mut` arguments;
//! - `control`: `if`, blocks, loops, `match`, `break`/`continue`/`return`;
//! - `calls`: methods of builtin types, constructors, glam's free
//!   functions, `#[rt_function]` helpers;
//! - `generic_calls`: calls of generic helpers, the instance's arguments
//!   inferred (see `lower/generics.rs`);
//! - `generic_structs`: literals of generic structs, the instance inferred
//!   (see `lower/generic_structs.rs`);
//! - `intrinsics`: intrinsic calls from the contract's rows;
//! - `buffers`: buffer and sampler access;
//! - `infer`: integer inference variables, coercion;
//! - `tuples`: tuple values, `let` and `match` over tuple patterns;
//! - `options`: `Option` values, `Some`/`None` and their methods;
//! - `tuple_structs`: `Rgb(a, b, c)` and its patterns;
//! - `resume`: the resumable form of a tracing function.
//!
//! This file holds the struct, the entry point ([`FnLowerer::function`]),
//! names and scopes, and the block walker.

use super::text::{self, indent, int_literal_placeholder, mark};
use super::value::{Place, Val, any_effects, any_reads, codes, f32_literal};
use super::{HelperSig, ModuleCtx, builtins, is_reserved};
use crate::error::{Error, Errors, Result};
use crate::kinds::{self, Kind};
use crate::types::{BOOL, BufferKind, F32, I32, Scalar, Ty, U32};
use proc_macro2::Span;
use std::collections::HashSet;
use syn::spanned::Spanned;
use syn::{BinOp, Expr, Stmt, UnOp};

mod bindless;
mod buffers;
mod callables;
mod calls;
mod control;
mod eval;
mod expr;
mod generic_calls;
mod generic_structs;
mod infer;
mod intrinsics;
mod operators;
mod ops;
mod options;
mod places;
mod probe;
mod resume;
mod sampler_ids;
mod stmt;
mod tuple_structs;
mod tuples;

use eval::int_literal_value;
use expr::strip_parens;
use ops::{Operands, compound_base, is_compound, op_symbol};
pub use stmt::count_placeholders;

#[derive(Clone, Debug)]
struct Local {
    wgsl: String,
    ty: Ty,
    /// Declared with `var` (assignable, addressable).
    var: bool,
}

/// The WGSL name of a local whose `let` failed (see `poison_pattern`).
const POISONED: &str = "<poisoned>";

/// What the function being lowered is.
pub enum FnRole {
    Program(Kind),
    Helper,
}

pub struct FnLowerer<'m> {
    m: &'m ModuleCtx,
    role: FnRole,
    fn_name: String,
    scopes: Vec<Vec<(String, Local)>>,
    names: HashSet<String>,
    ivars: Vec<(u32, Option<Scalar>)>,
    blocks: Vec<Block>,
    ret: Ty,
    loop_depth: u32,
    /// Lowering a function body (not a constant's initialiser, which has no
    /// statements to emit into).
    in_function: bool,
    /// What a `break` leaves, innermost last: a loop (`None`), or a `match`
    /// arm, a WGSL `switch` case, where `break` would leave the `switch`
    /// only: `Some((flag, used))`, set the flag, leave the `switch`, and
    /// test the flag after it.
    breaks: Vec<Option<(String, bool)>>,
    /// Per loop being lowered, innermost last: for a `loop`, the variable
    /// its `break value`s assign and the value's type, once the first is
    /// lowered (`Some(None)` before); `None` for `while` and `for`, which
    /// take no value.
    loop_values: Vec<Option<Option<(String, Ty)>>>,
    /// WGSL names of function-local `const` items (patterns name them).
    local_consts: HashSet<String>,
    /// Intrinsics called (directly, or through helpers) with the call span.
    pub intrinsics: Vec<(&'static str, Span)>,
    /// Helpers called.
    pub calls: Vec<String>,
    /// Calls only types resolve, by key, with the call's span: methods
    /// called as `value.name(..)` (`Type::name`) and instances of generic
    /// helpers (`lerp<Vec3>`); the helper order needs them (see
    /// `Unit::method_calls`).
    pub method_calls: Vec<(String, Span)>,
    /// Payload types passed to `rt_trace`.
    pub traced: Vec<Ty>,
    pub errors: Errors,
    /// Assignments that copy temporaries passed as `&mut` back to the field
    /// or element they stand for, emitted right after the call.
    writebacks: Vec<String>,
    /// Lowering the resumable form of a tracing program (see `resume`).
    resume: Option<resume::Resume>,
    /// Statements being lowered are directly in a block with a trace: their
    /// `let`s and `const`s go to the top of the function.
    hoist: bool,
    /// Calls taken out of expressions by the resumable form so far.
    hoisted_calls: usize,
    /// Tuple types whose integer elements were not inferred yet when they
    /// were built: declared by [`FnLowerer::finish`].
    pending_tuples: Vec<Ty>,
    /// Each expression lowered, by address, with its type before inference
    /// settled (the typed form, `crate::typed`).
    expr_types: std::collections::HashMap<usize, Ty>,
    /// The type the next `let` takes where it names none: that of a
    /// `let o = None;` found by a later use (`options.rs`).
    let_type_hint: Option<Ty>,
    /// While probing for that type: the local, and the type found.
    none_probe: Option<options::NoneProbe>,
}

/// The statements emitted into one block so far, each with whether it
/// may change state (anything but a `let` of a value without effects), for
/// [`FnLowerer::spill`].
#[derive(Default)]
struct Block {
    lines: Vec<String>,
    writes: Vec<bool>,
}

impl Block {
    fn push(&mut self, line: String, writes: bool) {
        self.insert(self.lines.len(), line, writes);
    }

    fn insert(&mut self, at: usize, line: String, writes: bool) {
        self.lines.insert(at, line);
        self.writes.insert(at, writes);
    }

    fn len(&self) -> usize {
        self.lines.len()
    }

    /// Whether a statement from `at` on may change state.
    fn writes_since(&self, at: usize) -> bool {
        self.writes[at..].iter().any(|w| *w)
    }

    /// The statements from `at` on, taken out.
    fn split_off(&mut self, at: usize) -> Vec<String> {
        self.writes.truncate(at);
        self.lines.split_off(at)
    }
}

/// A parameter as the lowering sees it.
pub struct LParam {
    pub rust: String,
    pub ty: Ty,
    pub mutable_binding: bool,
    pub span: Span,
}

impl<'m> FnLowerer<'m> {
    pub fn new(m: &'m ModuleCtx, role: FnRole, fn_name: &str, ret: Ty) -> Self {
        let mut names: HashSet<String> = HashSet::new();
        names.insert(fn_name.to_string());
        FnLowerer {
            m,
            role,
            fn_name: fn_name.to_string(),
            scopes: vec![Vec::new()],
            names,
            ivars: Vec::new(),
            blocks: vec![Block::default()],
            ret,
            loop_depth: 0,
            in_function: false,
            breaks: Vec::new(),
            loop_values: Vec::new(),
            local_consts: HashSet::new(),
            intrinsics: Vec::new(),
            calls: Vec::new(),
            method_calls: Vec::new(),
            traced: Vec::new(),
            errors: Errors::default(),
            writebacks: Vec::new(),
            resume: None,
            hoist: false,
            hoisted_calls: 0,
            pending_tuples: Vec::new(),
            expr_types: std::collections::HashMap::new(),
            let_type_hint: None,
            none_probe: None,
        }
    }

    fn kind(&self) -> Option<Kind> {
        match self.role {
            FnRole::Program(k) => Some(k),
            FnRole::Helper => None,
        }
    }

    /// Lowers a whole function: returns the WGSL text (with markers and
    /// placeholders still in; `ModuleCtx::finish_function` resolves them).
    pub fn function(&mut self, wgsl_name: &str, params: &[LParam], body: &syn::Block) -> String {
        self.in_function = true;
        let (sig, copies) = self.bind_params(params);
        let prologue = copies.into_iter().map(|(local, pname, _)| format!("var {local} = {pname};"));
        prologue.for_each(|line| self.emit(line));
        let ret = self.ret.clone();
        let tail = self.block_inner(&body.stmts, Some(&ret));
        match tail {
            Ok(Some(v)) => {
                if matches!(ret, Ty::Unit) {
                    if !matches!(v.ty, Ty::Unit | Ty::Never) {
                        self.emit(format!("_ = {};", v.code));
                    }
                } else if !matches!(v.ty, Ty::Never) {
                    match self.coerce(v, &ret, body_tail_span(body)) {
                        Ok(v) => self.emit(format!("return {};", v.code)),
                        Err(e) => self.errors.push(e),
                    }
                }
            }
            Ok(None) => {
                if !matches!(ret, Ty::Unit) && !ends_in_return(body) {
                    self.errors.push(Error::new(
                        body.brace_token.span.close(),
                        format!("this function must return a `{ret}` on every path"),
                    ));
                }
            }
            Err(e) => self.errors.push(e),
        }
        let lines = self.blocks.pop().unwrap().lines;
        let ret_text = if matches!(ret, Ty::Unit) { String::new() } else { format!(" -> {}", ret.wgsl()) };
        let def = text::site(&text::Site::Definition);
        format!("fn {wgsl_name}{def}({}){ret_text} {{\n{}}}\n", sig.join(", "), indent(&lines.join("\n")))
    }

    /// Binds the parameters: the signature's entries, and for each
    /// `mut` value parameter `(local, parameter, type)`, the local the
    /// body uses instead (WGSL parameters are immutable).
    fn bind_params(&mut self, params: &[LParam]) -> (Vec<String>, Vec<(String, String, Ty)>) {
        let mut sig = Vec::new();
        let mut copies = Vec::new();
        for p in params {
            let pname = self.fresh(&p.rust);
            sig.push(format!("{pname}: {}", p.ty.wgsl()));
            if p.mutable_binding && !matches!(p.ty, Ty::Ref(..)) {
                let local = self.fresh(&p.rust);
                self.bind(&p.rust, Local { wgsl: local.clone(), ty: p.ty.clone(), var: true });
                copies.push((local, pname, p.ty.clone()));
            } else {
                self.bind(&p.rust, Local { wgsl: pname, ty: p.ty.clone(), var: false });
            }
        }
        (sig, copies)
    }

    /// Resolves the placeholders of `text` with this function's inference
    /// variables and strips its markers (see [`text::finish`]).
    /// The tuple types still waiting for their integers are declared now.
    pub fn finish(&self, text: &str) -> text::Finished {
        for t in &self.pending_tuples {
            self.m.note_tuples(&self.settled(t));
        }
        text::finish(text, &|v| self.resolve_var(v) == Scalar::I32)
    }

    /// The typed form of `body`, which [`FnLowerer::function`] lowered:
    /// each expression's type with inference settled.
    pub fn typed(&self, body: &syn::Block) -> crate::typed::Typed {
        let settled = self.expr_types.iter().map(|(a, t)| (*a, self.settled(t))).collect();
        crate::typed::Typed::number(body, &settled)
    }

    /// Resolves an integer inference variable (default `i32`).
    pub fn resolve_var(&self, v: u32) -> Scalar {
        let root = self.find(v);
        self.ivars[root as usize].1.unwrap_or(Scalar::I32)
    }

    fn fresh(&mut self, base: &str) -> String {
        let base = if is_reserved(base) || base.starts_with("rt") || base.starts_with("__") || base == "_" {
            format!("{base}_")
        } else {
            base.to_string()
        };
        let mut name = base.clone();
        let mut n = 1;
        while self.names.contains(&name) || self.m.global_names.contains(&name) {
            name = format!("{base}_{n}");
            n += 1;
        }
        self.names.insert(name.clone());
        name
    }

    fn bind(&mut self, rust: &str, local: Local) {
        self.scopes.last_mut().unwrap().push((rust.to_string(), local));
    }

    /// Binds the names of a pattern whose `let` failed: their uses are
    /// silent errors.
    fn poison_pattern(&mut self, pat: &syn::Pat) {
        struct Names(Vec<String>);
        impl<'ast> syn::visit::Visit<'ast> for Names {
            fn visit_pat_ident(&mut self, p: &'ast syn::PatIdent) {
                self.0.push(p.ident.to_string());
                syn::visit::visit_pat_ident(self, p);
            }
        }
        let mut names = Names(Vec::new());
        syn::visit::Visit::visit_pat(&mut names, pat);
        for n in names.0 {
            self.bind(&n, Local { wgsl: POISONED.to_string(), ty: Ty::Never, var: false });
        }
    }

    fn lookup(&self, rust: &str) -> Option<&Local> {
        self.scopes.iter().rev().flat_map(|s| s.iter().rev()).find(|(n, _)| n == rust).map(|(_, l)| l)
    }

    /// Emits a statement that may change state.
    fn emit(&mut self, line: String) {
        self.blocks.last_mut().unwrap().push(line, true);
    }

    /// Emits `line`, a `let` of `value`: it changes state only if the
    /// value has effects.
    fn emit_let(&mut self, line: String, value: &Val) {
        self.blocks.last_mut().unwrap().push(line, value.effects);
    }

    fn mark(&self, span: Span, text: &str) -> String {
        mark(self.m.span_id(span), text)
    }

    fn tmp(&mut self) -> String {
        self.fresh("tmp")
    }

    /// Lowers statements in a new scope and buffer; returns the lines and
    /// the tail value.
    fn sub_block(&mut self, stmts: &[Stmt], want: Option<&Ty>) -> Result<(Vec<String>, Option<Val>)> {
        self.blocks.push(Block::default());
        self.scopes.push(Vec::new());
        let hoist = std::mem::replace(&mut self.hoist, false);
        let r = self.block_inner(stmts, want);
        self.hoist = hoist;
        self.scopes.pop();
        let lines = self.blocks.pop().unwrap().lines;
        r.map(|v| (lines, v))
    }

    /// Lowers statements into the current buffer; errors in a statement are
    /// recorded and lowering goes on with the next one.
    fn block_inner(&mut self, stmts: &[Stmt], want: Option<&Ty>) -> Result<Option<Val>> {
        let mut tail = None;
        for (i, s) in stmts.iter().enumerate() {
            let last = i + 1 == stmts.len();
            match s {
                Stmt::Expr(e, None) if last => match self.expr(e, want) {
                    Ok(v) => tail = Some(v),
                    Err(err) => {
                        self.errors.push(err);
                        // Already reported: not also "must return a value".
                        tail = Some(Val::new("", Ty::Never));
                    }
                },
                _ => {
                    if let Stmt::Local(l) = s {
                        self.let_type_hint = self.none_local_type(l, &stmts[i + 1..], want);
                    }
                    if let Err(err) = self.stmt(s) {
                        self.errors.push(err);
                    }
                    // `{ ...; return; }` has type `!` in Rust, like `{ return }`.
                    if last && matches!(s, Stmt::Expr(Expr::Return(_) | Expr::Break(_) | Expr::Continue(_), Some(_))) {
                        tail = Some(Val::new("", Ty::Never));
                    }
                }
            }
        }
        Ok(tail)
    }

    pub fn resolve_type(&self, ty: &syn::Type) -> Result<Ty> {
        self.m.resolve_type(ty)
    }
}

fn body_tail_span(b: &syn::Block) -> Span {
    b.stmts.last().map(|s| s.span()).unwrap_or(b.brace_token.span.join())
}

fn ends_in_return(b: &syn::Block) -> bool {
    fn diverges(e: &Expr) -> bool {
        match e {
            Expr::Return(_) => true,
            Expr::Loop(l) => !contains_break(&l.body.stmts),
            Expr::If(i) => match &i.else_branch {
                Some((_, e)) => block_diverges(&i.then_branch) && diverges(e),
                None => false,
            },
            Expr::Block(b) => block_diverges(&b.block),
            Expr::Match(m) => !m.arms.is_empty() && m.arms.iter().all(|a| diverges(&a.body)),
            _ => false,
        }
    }
    fn block_diverges(b: &syn::Block) -> bool {
        b.stmts.iter().any(|s| match s {
            Stmt::Expr(e, _) => diverges(e),
            _ => false,
        })
    }
    fn contains_break(stmts: &[Stmt]) -> bool {
        // Conservative: any `break` text inside the loop body.
        stmts.iter().any(|s| quote::quote!(#s).to_string().contains("break"))
    }
    block_diverges(b)
}
