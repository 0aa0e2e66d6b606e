//! Labelled loops (`'outer: for ..`, `break 'outer`, `continue 'outer`)
//! without labels, which WGSL has none of: a jump out of nested loops sets
//! a flag and leaves the innermost loop with a plain `break`; after each
//! statement that holds such a loop, a check passes the jump on, one loop
//! at a time, until the labelled loop's own body takes it as its `break`
//! or `continue`.
//!
//! ```text
//! 'a: for i in .. {            let mut f = 0u32;
//!     for j in .. {            for i in .. {
//!         break 'a;                for j in .. { f = 1u32; break; }
//!     }                            if f == 1u32 { break; }
//! }                                if f == 2u32 { f = 0u32; continue; }
//!                              }
//! ```

use proc_macro2::Span;
use syn::visit_mut::VisitMut;
use syn::{Expr, parse_quote_spanned};

/// The pass: innermost labelled loops first, so that each sees only the
/// jumps to its own label.
#[derive(Default)]
pub(super) struct Labels {
    fresh: u32,
}

impl VisitMut for Labels {
    fn visit_expr_mut(&mut self, e: &mut Expr) {
        syn::visit_mut::visit_expr_mut(self, e);
        let (label, body) = match e {
            Expr::ForLoop(f) => (f.label.take(), &mut f.body),
            Expr::While(w) => (w.label.take(), &mut w.body),
            Expr::Loop(l) => (l.label.take(), &mut l.body),
            _ => return,
        };
        let Some(label) = label else { return };
        let span = label.name.apostrophe;
        self.fresh += 1;
        let flag = syn::Ident::new(&format!("rt_sugar_jump{}", self.fresh), span);
        let mut jumps = Jumps { label: label.name.ident.to_string(), flag: flag.clone(), depth: 0, deepest: None };
        jumps.visit_block_mut(body);
        if jumps.deepest.is_some_and(|d| d > 0) {
            let looped = e.clone();
            *e = parse_quote_spanned! {span=> { let mut #flag: u32 = 0u32; #looped } };
        }
    }

    fn visit_expr_closure_mut(&mut self, _: &mut syn::ExprClosure) {}
}

/// The jumps to one label inside its loop's body, at `depth` loops below
/// it.
struct Jumps {
    label: String,
    flag: syn::Ident,
    depth: u32,
    /// The deepest loop (below the labelled one) a jump to the label was
    /// found in, in what has been visited since it was last reset.
    deepest: Option<u32>,
}

impl Jumps {
    fn found(&mut self) {
        self.deepest = Some(self.deepest.map_or(self.depth, |d| d.max(self.depth)));
    }

    fn is_ours(&self, l: &Option<syn::Lifetime>) -> bool {
        l.as_ref().is_some_and(|l| l.ident == self.label)
    }

    /// The check after a statement holding a loop that jumped: at the
    /// labelled loop's own level the jump itself, deeper a `break` that
    /// passes it on.
    fn check(&self, span: Span) -> syn::Stmt {
        let f = &self.flag;
        if self.depth == 0 {
            parse_quote_spanned! {span=>
                if #f != 0u32 { if #f == 1u32 { break; } #f = 0u32; continue; }
            }
        } else {
            parse_quote_spanned! {span=> if #f != 0u32 { break; } }
        }
    }
}

impl VisitMut for Jumps {
    fn visit_block_mut(&mut self, b: &mut syn::Block) {
        let mut stmts = Vec::with_capacity(b.stmts.len());
        for mut s in std::mem::take(&mut b.stmts) {
            let outer = self.deepest.take();
            self.visit_stmt_mut(&mut s);
            let inner = self.deepest;
            let span = syn::spanned::Spanned::span(&s);
            stmts.push(s);
            if inner.is_some_and(|d| d > self.depth) {
                stmts.push(self.check(span));
            }
            self.deepest = match (outer, inner) {
                (Some(a), Some(b)) => Some(a.max(b)),
                (a, b) => a.or(b),
            };
        }
        b.stmts = stmts;
    }

    fn visit_expr_mut(&mut self, e: &mut Expr) {
        let f = self.flag.clone();
        match e {
            Expr::Break(b) if self.is_ours(&b.label) && b.expr.is_none() => {
                self.found();
                let span = b.break_token.span;
                *e = if self.depth == 0 {
                    parse_quote_spanned!(span=> break)
                } else {
                    parse_quote_spanned!(span=> { #f = 1u32; break; })
                };
            }
            Expr::Continue(c) if self.is_ours(&c.label) => {
                self.found();
                let span = c.continue_token.span;
                *e = if self.depth == 0 {
                    parse_quote_spanned!(span=> continue)
                } else {
                    parse_quote_spanned!(span=> { #f = 2u32; break; })
                };
            }
            Expr::ForLoop(_) | Expr::While(_) | Expr::Loop(_) => {
                self.depth += 1;
                syn::visit_mut::visit_expr_mut(self, e);
                self.depth -= 1;
            }
            Expr::Closure(_) => {}
            _ => syn::visit_mut::visit_expr_mut(self, e),
        }
    }
}
