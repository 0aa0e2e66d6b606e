//! Closures bound to a name and called where they are in scope (`let f =
//! |a: f32| a * k; f(2.0)`), inlined at each call: the binding goes, and
//! each `f(x)` becomes the closure's body with its parameters bound to the
//! arguments (see `iterators::inline`).
//!
//! This is the closure's meaning because rustc keeps what it captures from
//! changing while it lives: a closure that reads `k` borrows it, so `k` is
//! the same at every call as at the binding, and one that writes `k`
//! borrows it mutably, so only its calls write it. A `move` closure copies
//! what it captures at the binding instead, so it is left alone, as is a
//! closure that is used other than by calling it (passed on, returned):
//! the lowering refuses those with its own message.

use super::iterators::inline;
use syn::visit::Visit;
use syn::visit_mut::VisitMut;
use syn::{Expr, Pat, Stmt};

/// Inlines, in `stmts`, the closures bound by `let` and only called after.
pub(super) fn inline_bound(stmts: &mut Vec<Stmt>) {
    let mut i = 0;
    while i < stmts.len() {
        if let Some((name, closure)) = bound_closure(&stmts[i])
            && only_called(&stmts[i + 1..], &name)
        {
            stmts.remove(i);
            let mut calls = Calls { name, closure };
            for s in stmts[i..].iter_mut() {
                let rebinds = rebinds(s, &calls.name);
                calls.visit_stmt_mut(s);
                if rebinds {
                    break;
                }
            }
            continue;
        }
        i += 1;
    }
}

/// `let name = |..| ..;`: the name and the closure (not a `move` one).
fn bound_closure(s: &Stmt) -> Option<(String, syn::ExprClosure)> {
    let Stmt::Local(l) = s else { return None };
    let Pat::Ident(pi) = &l.pat else { return None };
    let init = l.init.as_ref()?;
    let Expr::Closure(c) = &*init.expr else { return None };
    if c.capture.is_some() || init.diverge.is_some() || pi.by_ref.is_some() || pi.subpat.is_some() {
        return None;
    }
    Some((pi.ident.to_string(), c.clone()))
}

/// Whether `name`, in `stmts` up to a `let` that binds it again, is only
/// ever called, with the closure's number of arguments checked at the call.
fn only_called(stmts: &[Stmt], name: &str) -> bool {
    struct Uses<'a> {
        name: &'a str,
        other: bool,
    }
    impl<'ast> Visit<'ast> for Uses<'_> {
        fn visit_expr_call(&mut self, c: &'ast syn::ExprCall) {
            if is_name(&c.func, self.name) {
                for a in &c.args {
                    self.visit_expr(a);
                }
            } else {
                syn::visit::visit_expr_call(self, c);
            }
        }
        fn visit_expr_path(&mut self, p: &'ast syn::ExprPath) {
            if p.path.is_ident(self.name) {
                self.other = true;
            }
        }
        fn visit_macro(&mut self, m: &'ast syn::Macro) {
            // A macro's tokens may name it in any way.
            if m.tokens.to_string().split(|c: char| !c.is_alphanumeric() && c != '_').any(|w| w == self.name) {
                self.other = true;
            }
        }
    }
    let mut uses = Uses { name, other: false };
    for s in stmts {
        uses.visit_stmt(s);
        if rebinds(s, name) {
            break;
        }
    }
    !uses.other
}

/// Whether `s` is a `let` binding `name` again (from there on the name is
/// another value).
fn rebinds(s: &Stmt, name: &str) -> bool {
    struct Binds<'a>(&'a str, bool);
    impl<'ast> Visit<'ast> for Binds<'_> {
        fn visit_pat_ident(&mut self, p: &'ast syn::PatIdent) {
            self.1 |= p.ident == self.0;
        }
    }
    let Stmt::Local(l) = s else { return false };
    let mut b = Binds(name, false);
    b.visit_pat(&l.pat);
    b.1
}

fn is_name(e: &Expr, name: &str) -> bool {
    matches!(e, Expr::Path(p) if p.path.is_ident(name))
}

/// Replaces the calls of the closure bound to `name`.
struct Calls {
    name: String,
    closure: syn::ExprClosure,
}

impl VisitMut for Calls {
    fn visit_expr_mut(&mut self, e: &mut Expr) {
        syn::visit_mut::visit_expr_mut(self, e);
        if let Expr::Call(c) = e
            && is_name(&c.func, &self.name)
            && let Some(body) = inline(&self.closure, c.args.iter().cloned().collect())
        {
            *e = body;
        }
    }
}
