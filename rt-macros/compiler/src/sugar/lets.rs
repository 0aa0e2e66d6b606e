//! Patterns in `let` positions as the `match` they mean: `if let`,
//! `while let` and `let ... else`, so that they take the patterns `match`
//! takes (literals, ranges, `|`, enum variants, tuples, `Some`/`None`,
//! bindings) and nothing else.
//!
//! ```text
//! if let P = e { A } else { B }      match e { P => { A } _ => { B } }
//! 'l: while let P = e { A }          'l: loop { match e { P => { A } _ => break } }
//! let P = e else { D };              let (x, y) = match e { P => (x, y), _ => { D } };
//! ```
//!
//! The scrutinee is evaluated once, as in Rust. `let ... else` binds the
//! pattern's names (zero, one, or a tuple of them) from the `match`'s value;
//! rustc has checked on the CPU copy that `D` diverges. A `let` inside a
//! longer condition (`if let P = e && c`) is left for the lowering to refuse.

use super::Rewriter;
use syn::visit::Visit;
use syn::{Expr, parse_quote_spanned};

impl Rewriter {
    /// `if let P = e { .. } else ..` as a `match`; `None` for another `if`.
    pub(super) fn if_let(&mut self, i: &syn::ExprIf) -> Option<Expr> {
        let Expr::Let(l) = &*i.cond else { return None };
        let span = l.let_token.span;
        let (pat, scrutinee) = (&*l.pat, &*l.expr);
        let then = &i.then_branch;
        let otherwise: Expr = match &i.else_branch {
            Some((_, e)) => (**e).clone(),
            None => parse_quote_spanned!(span=> {}),
        };
        Some(self.chained(parse_quote_spanned! {span=>
            match #scrutinee {
                #pat => #then
                _ => #otherwise
            }
        }))
    }

    /// `while let P = e { .. }` as a `loop` over a `match`; `None` for a
    /// plain `while`.
    pub(super) fn while_let(&mut self, w: &syn::ExprWhile) -> Option<Expr> {
        let Expr::Let(l) = &*w.cond else { return None };
        let span = l.let_token.span;
        let (pat, scrutinee, body, label) = (&*l.pat, &*l.expr, &w.body, &w.label);
        let matched = self.chained(parse_quote_spanned! {span=>
            match #scrutinee {
                #pat => #body
                _ => break,
            }
        });
        Some(parse_quote_spanned! {span=>
            #label loop {
                #matched
            }
        })
    }

    /// `let P = e else { D };` as a `let` of the pattern's names from a
    /// `match` (or the bare `match` when it binds none); `None` for a `let`
    /// without `else`.
    pub(super) fn let_else(&mut self, l: &syn::Local) -> Option<syn::Stmt> {
        let init = l.init.as_ref()?;
        let (_, diverge) = init.diverge.as_ref()?;
        let span = l.let_token.span;
        let (pat, scrutinee): (&syn::Pat, Expr) = match &l.pat {
            // The annotation types the scrutinee.
            syn::Pat::Type(pt) => {
                let (t, ty, e) = (self.fresh("let", span), &pt.ty, &init.expr);
                (&pt.pat, parse_quote_spanned!(span=> { let #t: #ty = #e; #t }))
            }
            p => (p, (*init.expr).clone()),
        };
        let names = bindings(pat);
        let arm_pat = without_mut(pat);
        let idents = names.iter().map(|(id, _)| id);
        let (value, bound): (Expr, Option<syn::Pat>) = match names.as_slice() {
            [] => (parse_quote_spanned!(span=> {}), None),
            [(id, m)] => (parse_quote_spanned!(span=> #id), Some(parse_quote_spanned!(span=> #m #id))),
            _ => {
                let pats = names.iter().map(|(id, m)| quote::quote!(#m #id));
                (parse_quote_spanned!(span=> (#(#idents),*)), Some(parse_quote_spanned!(span=> (#(#pats),*))))
            }
        };
        let matched: Expr = parse_quote_spanned! {span=>
            match #scrutinee {
                #arm_pat => #value,
                _ => #diverge
            }
        };
        let matched = self.chained(matched);
        Some(match bound {
            Some(b) => parse_quote_spanned!(span=> let #b = #matched;),
            None => syn::Stmt::Expr(matched, Some(syn::Token![;](span))),
        })
    }

    /// A `match` with range patterns or guards as the `if` chain the
    /// lowering takes (see `patterns.rs`), any other as it is.
    fn chained(&mut self, e: Expr) -> Expr {
        match &e {
            Expr::Match(m) => self.match_chain(m).unwrap_or(e),
            _ => e,
        }
    }
}

/// The names a pattern binds, in order, each once, with its `mut`: an
/// identifier that does not start with a capital (a capitalised one is a
/// constant or a unit variant, as `patterns.rs` reads it).
fn bindings(pat: &syn::Pat) -> Vec<(syn::Ident, Option<syn::Token![mut]>)> {
    struct Names(Vec<(syn::Ident, Option<syn::Token![mut]>)>);
    impl<'ast> Visit<'ast> for Names {
        fn visit_pat_ident(&mut self, p: &'ast syn::PatIdent) {
            let name = p.ident.to_string();
            let capital = name.chars().next().is_some_and(|c| c.is_ascii_uppercase());
            if !capital && !self.0.iter().any(|(id, _)| *id == name) {
                self.0.push((p.ident.clone(), p.mutability));
            }
            syn::visit::visit_pat_ident(self, p);
        }
        fn visit_expr(&mut self, _: &'ast Expr) {}
    }
    let mut names = Names(Vec::new());
    names.visit_pat(pat);
    names.0
}

/// `pat` with `mut` taken off its bindings: the match arm only reads them.
fn without_mut(pat: &syn::Pat) -> syn::Pat {
    struct Strip;
    impl syn::visit_mut::VisitMut for Strip {
        fn visit_pat_ident_mut(&mut self, p: &mut syn::PatIdent) {
            p.mutability = None;
            syn::visit_mut::visit_pat_ident_mut(self, p);
        }
    }
    let mut p = pat.clone();
    syn::visit_mut::VisitMut::visit_pat_mut(&mut Strip, &mut p);
    p
}
