//! The typed form of a program body: every expression of the body the
//! lowering walked (after `sugar/`), with the type the lowering gave it once
//! integer inference settled, as rustc keeps its typeck results beside its
//! HIR. A writer that needs types (the lane-wise CPU form) walks the same
//! body and reads them here instead of typing the subset a second time.
//!
//! Expressions are numbered in the order `syn::visit` meets them, so any
//! copy of [`Typed::body`] can be read; an expression the lowering did not
//! type itself (a function's path in a call, a macro's arguments, one the
//! lowering rebuilt before typing) has no entry, and a reader must not
//! guess one.

use crate::types::Ty;
use std::collections::HashMap;
use syn::visit::Visit;

/// A body and its expressions' types.
#[derive(Clone, Debug)]
pub struct Typed {
    /// The body as the lowering walked it.
    pub body: syn::Block,
    /// By expression number (`syn::visit` order over `body`).
    pub types: Vec<Option<Ty>>,
}

impl Typed {
    /// Numbers `body`'s expressions and takes each one's type from `by_address`
    /// (keyed by the address of the expression the lowering was given,
    /// which must be in `body` itself, not a copy).
    pub fn number(body: &syn::Block, by_address: &HashMap<usize, Ty>) -> Typed {
        let types = expressions(body).into_iter().map(|e| by_address.get(&address(e)).cloned()).collect();
        Typed { body: body.clone(), types }
    }

    /// The type of each expression of [`Typed::body`], with the expression,
    /// in number order.
    pub fn typed_expressions(&self) -> impl Iterator<Item = (&syn::Expr, Option<&Ty>)> {
        expressions(&self.body).into_iter().zip(self.types.iter().map(Option::as_ref))
    }
}

/// The identity of an expression while its tree is alive.
pub fn address(e: &syn::Expr) -> usize {
    e as *const syn::Expr as usize
}

/// `body`'s expressions in `syn::visit` order.
fn expressions(body: &syn::Block) -> Vec<&syn::Expr> {
    struct Walk<'a>(Vec<&'a syn::Expr>);
    impl<'a> Visit<'a> for Walk<'a> {
        fn visit_expr(&mut self, e: &'a syn::Expr) {
            self.0.push(e);
            syn::visit::visit_expr(self, e);
        }
    }
    let mut walk = Walk(Vec::new());
    walk.visit_block(body);
    walk.0
}
