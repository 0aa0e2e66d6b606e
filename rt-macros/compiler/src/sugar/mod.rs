//! Rust that means a plain loop or an `if` chain, rewritten syn to syn
//! before the lowering types it, so the lowering sees only the subset's
//! core: closures bound to a name, inlined at their calls (`closures.rs`);
//! iterator loops and reductions over ranges and fixed arrays
//! (`iterators.rs`), `matches!` and the arms the lowering's `switch` cannot
//! take, range patterns and guards (`patterns.rs`); `if let`, `while let`
//! and `let ... else` as that `match` (`lets.rs`); `Option`'s methods that
//! take closures, as a `match` too (`options.rs`); then labelled loops,
//! as flags (`labels.rs`). Functions declared in a body are taken out to
//! be helpers (`nested.rs`). Before all of these, a call that gives a
//! generic helper a closure is inlined where it is written
//! (`closure_args.rs`).
//!
//! Only the WGSL side reads the rewritten form. The CPU copy of a program
//! is the function as written, compiled by rustc, so each rewrite must mean
//! what rustc means (the differential tests run both), and rustc checks
//! what the rewrite takes on trust: borrows, exhaustiveness, the types of
//! closures. Spans are the user's own, so an error in rewritten code points
//! at what the user wrote.

mod closure_args;
mod closures;
mod iterators;
mod labels;
mod lets;
mod nested;
mod options;
mod patterns;

pub use closure_args::{ClosureHelpers, is_closure_param, takes_closure};
pub(crate) use options::{is_none_path, is_some_path};

use crate::Item;
use crate::error::Errors;
use std::collections::HashSet;
use syn::visit_mut::VisitMut;

/// `f` with its sugar rewritten, and the functions declared in its body
/// (their names not in `taken`) taken out, rewritten too, into `nested`.
pub fn function(
    f: &syn::ItemFn,
    taken: &mut HashSet<String>,
    nested: &mut Vec<syn::ItemFn>,
    cx: &mut Cx,
) -> syn::ItemFn {
    let mut f = f.clone();
    body(&mut f.block, None, taken, nested, cx);
    f
}

/// What the rewrites of a unit share: the helpers that take closures
/// (whose calls are inlined), and the errors of those calls.
pub struct Cx {
    pub closures: ClosureHelpers,
    /// The calls inlined so far (their names' suffix).
    pub inlined: u32,
    pub errors: Errors,
}

/// A function's body rewritten, its nested functions taken out into
/// `nested` (rewritten too).
/// `owner` is the type a method's block is for.
fn body(
    b: &mut syn::Block,
    owner: Option<&str>,
    taken: &mut HashSet<String>,
    nested: &mut Vec<syn::ItemFn>,
    cx: &mut Cx,
) {
    cx.closures.inline(b, owner, &mut cx.inlined, &mut cx.errors);
    let mut inner = Vec::new();
    nested::hoist(b, taken, &mut inner);
    for mut g in inner {
        block(&mut g.block);
        nested.push(g);
    }
    block(b);
}

/// Both passes over a function's body.
fn block(b: &mut syn::Block) {
    Rewriter::default().visit_block_mut(b);
    labels::Labels::default().visit_block_mut(b);
}

/// `item` with the sugar of its functions and methods rewritten (and
/// their nested functions taken out, as [`function`] does).
pub fn item(item: &Item, taken: &mut HashSet<String>, nested: &mut Vec<syn::ItemFn>, cx: &mut Cx) -> Item {
    match item {
        Item::Function(f) => Item::Function(function(f, taken, nested, cx)),
        Item::Impl(i) => {
            let mut i = i.clone();
            let owner = crate::methods::self_name(&i);
            for it in &mut i.items {
                if let syn::ImplItem::Fn(f) = it {
                    body(&mut f.block, owner.as_deref(), taken, nested, cx);
                }
            }
            Item::Impl(i)
        }
        other => other.clone(),
    }
}

/// The rewriting pass: innermost expressions first, so that a rewrite sees
/// rewritten operands. Names it introduces start with `rt_sugar_`, which
/// user code does not spell (and which WGSL takes: `__` it reserves).
#[derive(Default)]
struct Rewriter {
    fresh: u32,
}

impl Rewriter {
    /// A fresh local name, `rt_sugar_<what><n>`.
    fn fresh(&mut self, what: &str, span: proc_macro2::Span) -> syn::Ident {
        self.fresh += 1;
        syn::Ident::new(&format!("rt_sugar_{what}{}", self.fresh), span)
    }
}

impl VisitMut for Rewriter {
    fn visit_block_mut(&mut self, b: &mut syn::Block) {
        closures::inline_bound(&mut b.stmts);
        syn::visit_mut::visit_block_mut(self, b);
    }

    fn visit_expr_mut(&mut self, e: &mut syn::Expr) {
        // `matches!`'s tokens are opaque to the visit: the `match` it
        // stands for is visited instead.
        if let syn::Expr::Macro(m) = e
            && let Some(r) = self.matches_macro(&m.mac)
        {
            *e = r;
        }
        syn::visit_mut::visit_expr_mut(self, e);
        let rewritten = match e {
            syn::Expr::ForLoop(f) => self.for_loop(f),
            syn::Expr::MethodCall(m) => {
                self.reduction(m).or_else(|| self.option_reduction(m)).or_else(|| self.option_closure(m))
            }
            syn::Expr::Match(m) => self.match_chain(m),
            syn::Expr::If(i) => self.if_let(i).or_else(|| self.none_first(i)),
            syn::Expr::While(w) => self.while_let(w),
            _ => None,
        };
        if let Some(r) = rewritten {
            *e = r;
        }
    }

    fn visit_stmt_mut(&mut self, s: &mut syn::Stmt) {
        // `matches!(..)` as a statement's expression is a `Stmt::Macro`.
        if let syn::Stmt::Macro(m) = s
            && let Some(r) = self.matches_macro(&m.mac)
        {
            *s = syn::Stmt::Expr(r, m.semi_token);
        }
        syn::visit_mut::visit_stmt_mut(self, s);
        if let syn::Stmt::Local(l) = s
            && let Some(r) = self.let_else(l)
        {
            *s = r;
        }
    }
}
