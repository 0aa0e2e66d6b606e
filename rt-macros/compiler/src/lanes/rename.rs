//! A statement as one lane runs it: each lane-wise local `x` read or
//! written as `x[__l]`, its value in lane `__l`. Names bound inside the
//! statement (closure parameters, `match` arms, `for` patterns, inner
//! `let`s, `if let`) shadow the locals they share a name with, as in Rust.
//! Optionally a `return` of the program becomes `return true` (the lane
//! returned; see `rt_std::cpu::lanes::each`).

use super::Refusal;
use proc_macro2::TokenStream;
use quote::ToTokens;
use std::collections::HashSet;
use syn::punctuated::Punctuated;
use syn::spanned::Spanned;
use syn::visit_mut::{self, VisitMut};

/// Rewrites `e` for one lane: see the module's doc. `returns`: rewrite the
/// program's `return`s (outside closures).
pub(super) fn for_lane(e: &mut syn::Expr, varying: &HashSet<String>, returns: bool) -> Result<(), Refusal> {
    let mut r = Rename { varying, shadow: Vec::new(), closures: 0, returns, refused: None };
    r.visit_expr_mut(e);
    r.refused.map_or(Ok(()), Err)
}

/// The identifiers a pattern binds.
pub(super) fn bound(p: &syn::Pat) -> Vec<syn::Ident> {
    struct B(Vec<syn::Ident>);
    impl<'a> syn::visit::Visit<'a> for B {
        fn visit_pat_ident(&mut self, p: &'a syn::PatIdent) {
            self.0.push(p.ident.clone());
            syn::visit::visit_pat_ident(self, p);
        }
    }
    let mut b = B(Vec::new());
    syn::visit::Visit::visit_pat(&mut b, p);
    b.0
}

struct Rename<'a> {
    varying: &'a HashSet<String>,
    /// Names bound inside the statement, innermost scope last.
    shadow: Vec<HashSet<String>>,
    closures: usize,
    returns: bool,
    refused: Option<Refusal>,
}

impl Rename<'_> {
    fn lane_wise(&self, name: &str) -> bool {
        self.varying.contains(name) && !self.shadow.iter().any(|s| s.contains(name))
    }

    fn scoped(&mut self, names: Vec<syn::Ident>, f: impl FnOnce(&mut Self)) {
        self.shadow.push(names.iter().map(|i| i.to_string()).collect());
        f(self);
        self.shadow.pop();
    }

    /// A macro's arguments, renamed when they are expressions; a macro
    /// whose tokens are not expressions and name a lane-wise local is
    /// refused.
    fn macro_tokens(&mut self, m: &mut syn::Macro) {
        if m.path.is_ident("matches") {
            return self.matches_tokens(m);
        }
        let parser = Punctuated::<syn::Expr, syn::Token![,]>::parse_terminated;
        match syn::parse::Parser::parse2(parser, m.tokens.clone()) {
            Ok(mut args) => {
                for a in args.iter_mut() {
                    self.visit_expr_mut(a);
                }
                m.tokens = args.to_token_stream();
            }
            Err(_) if self.names_local(&m.tokens) => {
                let name = m.path.segments.last().map(|s| s.ident.to_string()).unwrap_or_default();
                self.refused.get_or_insert(Refusal::new(
                    m.span(),
                    format!("the macro `{name}!` takes a local in tokens that are not expressions"),
                ));
            }
            Err(_) => {}
        }
    }

    /// `matches!(value, pattern)`: the value renamed; a pattern (or guard)
    /// that names a lane-wise local is refused, since a pattern's names
    /// are bindings and a guard's are not.
    fn matches_tokens(&mut self, m: &mut syn::Macro) {
        let parser = |input: syn::parse::ParseStream| -> syn::Result<(syn::Expr, TokenStream)> {
            let value = input.parse()?;
            let rest: TokenStream = input.parse()?;
            Ok((value, rest))
        };
        match syn::parse::Parser::parse2(parser, m.tokens.clone()) {
            Ok((mut value, rest)) if !self.names_local(&rest) => {
                self.visit_expr_mut(&mut value);
                m.tokens = quote::quote!(#value #rest);
            }
            _ => {
                self.refused.get_or_insert(Refusal::new(m.span(), "a `matches!` pattern that names a local".into()));
            }
        }
    }

    fn names_local(&self, tokens: &TokenStream) -> bool {
        tokens.clone().into_iter().any(|t| match t {
            proc_macro2::TokenTree::Ident(i) => self.lane_wise(&i.to_string()),
            proc_macro2::TokenTree::Group(g) => self.names_local(&g.stream()),
            _ => false,
        })
    }
}

impl VisitMut for Rename<'_> {
    fn visit_expr_mut(&mut self, e: &mut syn::Expr) {
        match e {
            syn::Expr::Path(p)
                if p.qself.is_none() && p.path.leading_colon.is_none() && p.path.segments.len() == 1 && {
                    let s = &p.path.segments[0];
                    s.arguments.is_none() && self.lane_wise(&s.ident.to_string())
                } =>
            {
                // `__l` as the entry writes it (call-site hygiene), not as
                // the user's tokens have it (a `macro_rules!` caller's).
                let id = &p.path.segments[0].ident;
                let lane = syn::Ident::new("__l", proc_macro2::Span::call_site());
                *e = syn::parse_quote!(#id[#lane]);
            }
            syn::Expr::Closure(c) => {
                let names = c.inputs.iter().flat_map(bound).collect();
                self.closures += 1;
                self.scoped(names, |r| r.visit_expr_mut(&mut c.body));
                self.closures -= 1;
            }
            syn::Expr::Return(r) if self.returns && self.closures == 0 => {
                if r.expr.is_some() {
                    self.refused.get_or_insert(Refusal::new(r.span(), "a `return` with a value".into()));
                }
                *e = syn::parse_quote_spanned!(r.span()=> return true);
            }
            syn::Expr::ForLoop(f) => {
                self.visit_expr_mut(&mut f.expr);
                let names = bound(&f.pat);
                self.scoped(names, |r| r.visit_block_mut(&mut f.body));
            }
            syn::Expr::Match(m) => {
                self.visit_expr_mut(&mut m.expr);
                for arm in m.arms.iter_mut() {
                    let names = bound(&arm.pat);
                    self.scoped(names, |r| {
                        if let Some((_, g)) = &mut arm.guard {
                            r.visit_expr_mut(g);
                        }
                        r.visit_expr_mut(&mut arm.body);
                    });
                }
            }
            syn::Expr::If(i) => {
                self.visit_expr_mut(&mut i.cond);
                let names = let_bindings(&i.cond);
                self.scoped(names, |r| r.visit_block_mut(&mut i.then_branch));
                if let Some((_, els)) = &mut i.else_branch {
                    self.visit_expr_mut(els);
                }
            }
            syn::Expr::While(w) => {
                self.visit_expr_mut(&mut w.cond);
                let names = let_bindings(&w.cond);
                self.scoped(names, |r| r.visit_block_mut(&mut w.body));
            }
            syn::Expr::Macro(m) => self.macro_tokens(&mut m.mac),
            _ => visit_mut::visit_expr_mut(self, e),
        }
    }

    fn visit_block_mut(&mut self, b: &mut syn::Block) {
        self.shadow.push(HashSet::new());
        for s in b.stmts.iter_mut() {
            match s {
                syn::Stmt::Local(l) => {
                    if let Some(init) = &mut l.init {
                        self.visit_expr_mut(&mut init.expr);
                        if let Some((_, els)) = &mut init.diverge {
                            self.visit_expr_mut(els);
                        }
                    }
                    let names = bound(&l.pat);
                    if let Some(top) = self.shadow.last_mut() {
                        top.extend(names.iter().map(|i| i.to_string()));
                    }
                }
                syn::Stmt::Macro(m) => self.macro_tokens(&mut m.mac),
                syn::Stmt::Item(_) => {}
                syn::Stmt::Expr(e, _) => self.visit_expr_mut(e),
            }
        }
        self.shadow.pop();
    }

    fn visit_field_value_mut(&mut self, f: &mut syn::FieldValue) {
        // `S { x }` names the local `x`: written out, it becomes `x: x[__l]`.
        if f.colon_token.is_none()
            && let syn::Member::Named(id) = &f.member
            && self.lane_wise(&id.to_string())
        {
            f.colon_token = Some(Default::default());
        }
        self.visit_expr_mut(&mut f.expr);
    }

    fn visit_item_mut(&mut self, _: &mut syn::Item) {}
}

/// The names `let` conditions (`if let`, `while let`, `&&` chains of them)
/// bind for the branch they guard.
fn let_bindings(cond: &syn::Expr) -> Vec<syn::Ident> {
    match cond {
        syn::Expr::Let(l) => bound(&l.pat),
        syn::Expr::Binary(b) if matches!(b.op, syn::BinOp::And(_)) => {
            let mut v = let_bindings(&b.left);
            v.extend(let_bindings(&b.right));
            v
        }
        syn::Expr::Paren(p) => let_bindings(&p.expr),
        _ => Vec::new(),
    }
}
