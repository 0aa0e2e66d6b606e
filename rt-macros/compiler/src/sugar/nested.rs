//! Functions declared inside a function's body (`fn inner(..) {..}` in a
//! program or helper), taken out to stand beside it as helpers, which is
//! what they are: a nested `fn` sees nothing of the function around it.
//! One whose name another helper of the unit already has stays where it
//! is, and the lowering refuses it (WGSL has one namespace of functions).

use std::collections::HashSet;
use syn::visit_mut::VisitMut;

/// Takes the nested functions out of `b` (and out of those, in turn),
/// each whose name is not in `taken` (which gains it), into `out`.
pub(super) fn hoist(b: &mut syn::Block, taken: &mut HashSet<String>, out: &mut Vec<syn::ItemFn>) {
    let mut h = Hoist { taken, out };
    h.visit_block_mut(b);
}

struct Hoist<'a> {
    taken: &'a mut HashSet<String>,
    out: &'a mut Vec<syn::ItemFn>,
}

impl VisitMut for Hoist<'_> {
    fn visit_block_mut(&mut self, b: &mut syn::Block) {
        let mut kept = Vec::with_capacity(b.stmts.len());
        for s in std::mem::take(&mut b.stmts) {
            match s {
                syn::Stmt::Item(syn::Item::Fn(mut f)) if self.taken.insert(f.sig.ident.to_string()) => {
                    self.visit_block_mut(&mut f.block);
                    self.out.push(f);
                }
                s => kept.push(s),
            }
        }
        b.stmts = kept;
        syn::visit_mut::visit_block_mut(self, b);
    }

    fn visit_expr_closure_mut(&mut self, _: &mut syn::ExprClosure) {}
}
