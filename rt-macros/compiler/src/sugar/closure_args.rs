//! Closures passed to a generic helper (`#[rt_function] fn apply<F:
//! Fn(f32) -> f32>(f: F, x: f32)`, or `f: impl Fn(f32) -> f32`), called as
//! `apply(|a| a * k, x)`: WGSL has no function values, so the call is
//! inlined where it is written, as a block that binds each parameter to
//! its argument, in order, and then runs the helper's body. The closure,
//! bound by `let`, is then inlined at its calls as any bound closure is
//! (`closures.rs`).
//!
//! The helper's own names are renamed apart (`y` becomes `y_rt_inl3`), so
//! that a name the closure captures from the caller means the caller's
//! inside the inlined body too. What such a body cannot do is refused at
//! the call, naming the helper: an early `return` (the block has no
//! function to leave), a reference parameter, a type parameter named in
//! the body other than in a `let`'s annotation (the block cannot name it),
//! a closure parameter given something other than a closure written there.
//!
//! The CPU copy is the helper as written, called with the closure, which
//! is what the block means.

use super::iterators::{FirstReturn, unparen};
use crate::error::{Error, Errors};
use std::collections::{HashMap, HashSet};
use std::rc::Rc;
use syn::spanned::Spanned;
use syn::visit::Visit;
use syn::visit_mut::VisitMut;

/// How deep helpers given closures may inline into each other.
const MAX_DEPTH: u32 = 8;

/// The helpers that take a closure, by name, with whether each of their
/// parameters is a closure (shared: a block that declares more extends a
/// copy).
#[derive(Clone, Default)]
pub struct ClosureHelpers(HashMap<String, Rc<(syn::ItemFn, Vec<bool>)>>);

impl ClosureHelpers {
    /// Those among `fns`.
    pub fn new<'a>(fns: impl Iterator<Item = &'a syn::ItemFn>) -> ClosureHelpers {
        let mut h = ClosureHelpers::default();
        h.extend(fns);
        h
    }

    fn extend<'a>(&mut self, fns: impl Iterator<Item = &'a syn::ItemFn>) {
        for f in fns {
            let roles: Vec<bool> = f.sig.inputs.iter().map(|a| is_closure_param(f, a)).collect();
            if roles.iter().any(|r| *r) {
                self.0.insert(f.sig.ident.to_string(), Rc::new((f.clone(), roles)));
            }
        }
    }

    /// Inlines, in `b`, each call of one of these helpers or of those a
    /// block declares; `next` numbers the inlined calls of the unit.
    pub fn inline(&self, b: &mut syn::Block, next: &mut u32, errors: &mut Errors) {
        let mut v = Inliner { helpers: self.clone(), next: *next, depth: 0, errors };
        v.visit_block_mut(b);
        *next = v.next;
    }
}

/// Whether `f` has a parameter of a closure's type ([`is_closure_param`]).
pub fn takes_closure(f: &syn::ItemFn) -> bool {
    f.sig.inputs.iter().any(|a| is_closure_param(f, a))
}

/// Whether `arg` of `f` has a closure's type: `impl Fn(..)` (or `FnMut`,
/// `FnOnce`), or a type parameter bounded by one.
pub fn is_closure_param(f: &syn::ItemFn, arg: &syn::FnArg) -> bool {
    let syn::FnArg::Typed(pt) = arg else { return false };
    let is_fn_bound = |b: &syn::TypeParamBound| {
        matches!(b, syn::TypeParamBound::Trait(t)
            if t.path.segments.last().is_some_and(|s| matches!(s.ident.to_string().as_str(), "Fn" | "FnMut" | "FnOnce")))
    };
    match &*pt.ty {
        syn::Type::ImplTrait(it) => it.bounds.iter().any(is_fn_bound),
        syn::Type::Path(p) if p.qself.is_none() && p.path.segments.len() == 1 => {
            let name = &p.path.segments[0].ident;
            let in_params =
                f.sig.generics.type_params().any(|tp| tp.ident == *name && tp.bounds.iter().any(is_fn_bound));
            let in_where = f.sig.generics.where_clause.iter().flat_map(|w| &w.predicates).any(|pr| {
                matches!(pr, syn::WherePredicate::Type(t)
                    if matches!(&t.bounded_ty, syn::Type::Path(b) if b.path.is_ident(name))
                        && t.bounds.iter().any(is_fn_bound))
            });
            in_params || in_where
        }
        _ => false,
    }
}

struct Inliner<'e> {
    helpers: ClosureHelpers,
    next: u32,
    depth: u32,
    errors: &'e mut Errors,
}

impl VisitMut for Inliner<'_> {
    fn visit_block_mut(&mut self, b: &mut syn::Block) {
        // The helpers a block declares are seen in all of it.
        let declared: Vec<&syn::ItemFn> = b
            .stmts
            .iter()
            .filter_map(|s| match s {
                syn::Stmt::Item(syn::Item::Fn(f)) if takes_closure(f) => Some(f),
                _ => None,
            })
            .collect();
        if declared.is_empty() {
            return syn::visit_mut::visit_block_mut(self, b);
        }
        let outer = self.helpers.clone();
        self.helpers.extend(declared.into_iter());
        syn::visit_mut::visit_block_mut(self, b);
        self.helpers = outer;
    }

    fn visit_expr_mut(&mut self, e: &mut syn::Expr) {
        syn::visit_mut::visit_expr_mut(self, e);
        let syn::Expr::Call(call) = e else { return };
        let syn::Expr::Path(p) = &*call.func else { return };
        if p.qself.is_some() || p.path.segments.len() != 1 {
            return;
        }
        let Some(found) = self.helpers.0.get(&p.path.segments[0].ident.to_string()).cloned() else { return };
        let (helper, roles) = &*found;
        if roles.len() != call.args.len() {
            return; // rustc's error
        }
        match self.inlined(helper, roles, call) {
            Ok(mut block) => {
                self.depth += 1;
                if self.depth > MAX_DEPTH {
                    self.errors.0.push(Error::new(
                        call.span(),
                        format!(
                            "`{}` is given closures through helpers given closures too deep to inline",
                            helper.sig.ident
                        ),
                    ));
                } else {
                    self.visit_block_mut(&mut block);
                }
                self.depth -= 1;
                *e = syn::Expr::Block(syn::ExprBlock { attrs: Vec::new(), label: None, block });
            }
            Err(err) => self.errors.0.push(err),
        }
    }
}

impl Inliner<'_> {
    /// The block `call` of `helper` stands for (see the module's doc).
    fn inlined(&mut self, helper: &syn::ItemFn, roles: &[bool], call: &syn::ExprCall) -> Result<syn::Block, Error> {
        let name = &helper.sig.ident;
        let refuse = |span: proc_macro2::Span, what: &str| {
            Error::new(span, format!("`{name}` is given a closure, so it is inlined where it is called, and {what}"))
        };
        self.next += 1;
        let suffix = format!("_rt_inl{}", self.next);
        let mut body = (*helper.block).clone();
        let type_params: HashSet<String> = helper.sig.generics.type_params().map(|t| t.ident.to_string()).collect();
        strip_annotations(&mut body, &type_params);
        let mut early = FirstReturn(None);
        early.visit_block(&body);
        if let Some(span) = early.0 {
            return Err(refuse(span, "its body returns early: give it one value at its end"));
        }
        let mut named = FirstNamed(&type_params, None);
        named.visit_block(&body);
        if let Some(t) = named.1 {
            return Err(refuse(t.span(), &format!("its body names its type parameter `{t}`: name the type")));
        }
        let mut names = HashSet::new();
        let mut lets: Vec<syn::Stmt> = Vec::new();
        for ((input, is_closure), arg) in helper.sig.inputs.iter().zip(roles).zip(&call.args) {
            let syn::FnArg::Typed(pt) = input else {
                return Err(refuse(input.span(), "it takes `self`"));
            };
            let syn::Pat::Ident(pi) = &*pt.pat else {
                return Err(refuse(pt.pat.span(), "this parameter is a pattern: name it"));
            };
            if matches!(&*pt.ty, syn::Type::Reference(_)) {
                return Err(refuse(pt.ty.span(), "it takes a reference: pass the value and return the result"));
            }
            if *is_closure && !matches!(unparen(arg), syn::Expr::Closure(_)) {
                return Err(Error::new(
                    arg.span(),
                    format!(
                        "a closure given to `{name}` is inlined where it is written: pass the closure itself here \
                         (`{name}(|..| .., ..)`), not a name bound to one"
                    ),
                ));
            }
            names.insert(pi.ident.to_string());
            let ident = syn::Ident::new(&format!("{}{suffix}", pi.ident), pi.ident.span());
            let mutability = pi.mutability;
            lets.push(syn::parse_quote!(let #mutability #ident = #arg;));
        }
        Locals(&mut names).visit_block(&body);
        Rename { names: &names, suffix: &suffix }.visit_block_mut(&mut body);
        lets.extend(body.stmts);
        Ok(syn::Block { brace_token: body.brace_token, stmts: lets })
    }
}

/// Drops the annotation of each `let` whose type names one of
/// `type_params` (the value's own type stands in for it).
fn strip_annotations(b: &mut syn::Block, type_params: &HashSet<String>) {
    struct Strip<'a>(&'a HashSet<String>);
    impl VisitMut for Strip<'_> {
        fn visit_local_mut(&mut self, l: &mut syn::Local) {
            if let syn::Pat::Type(pt) = &l.pat
                && names_any(&pt.ty, self.0)
            {
                l.pat = (*pt.pat).clone();
            }
            syn::visit_mut::visit_local_mut(self, l);
        }
    }
    Strip(type_params).visit_block_mut(b);
}

/// Whether `ty` names one of `names`.
fn names_any(ty: &syn::Type, names: &HashSet<String>) -> bool {
    let mut f = FirstNamed(names, None);
    f.visit_type(ty);
    f.1.is_some()
}

/// A visit that finds the first identifier among a set of names.
struct FirstNamed<'a>(&'a HashSet<String>, Option<syn::Ident>);

impl<'ast> Visit<'ast> for FirstNamed<'_> {
    fn visit_ident(&mut self, i: &'ast syn::Ident) {
        if self.1.is_none() && self.0.contains(&i.to_string()) {
            self.1 = Some(i.clone());
        }
    }
}

/// The names `b` binds (a local's name starts in lower case; a capital
/// in a pattern is a constant or a variant).
struct Locals<'a>(&'a mut HashSet<String>);

impl<'ast> Visit<'ast> for Locals<'_> {
    fn visit_pat_ident(&mut self, p: &'ast syn::PatIdent) {
        let name = p.ident.to_string();
        if name.starts_with(|c: char| c.is_lowercase() || c == '_') {
            self.0.insert(name);
        }
        syn::visit::visit_pat_ident(self, p);
    }
}

/// Renames the bindings `names` and their uses by `suffix`.
struct Rename<'a> {
    names: &'a HashSet<String>,
    suffix: &'a str,
}

impl Rename<'_> {
    fn renamed(&self, i: &syn::Ident) -> Option<syn::Ident> {
        self.names.contains(&i.to_string()).then(|| syn::Ident::new(&format!("{i}{}", self.suffix), i.span()))
    }
}

impl Rename<'_> {
    fn tokens(&self, ts: proc_macro2::TokenStream) -> proc_macro2::TokenStream {
        use proc_macro2::{Group, TokenTree};
        ts.into_iter()
            .map(|t| match t {
                TokenTree::Ident(i) => TokenTree::Ident(self.renamed(&i).unwrap_or(i)),
                TokenTree::Group(g) => {
                    let mut n = Group::new(g.delimiter(), self.tokens(g.stream()));
                    n.set_span(g.span());
                    TokenTree::Group(n)
                }
                other => other,
            })
            .collect()
    }
}

impl VisitMut for Rename<'_> {
    fn visit_pat_ident_mut(&mut self, p: &mut syn::PatIdent) {
        if let Some(r) = self.renamed(&p.ident) {
            p.ident = r;
        }
        syn::visit_mut::visit_pat_ident_mut(self, p);
    }

    fn visit_expr_path_mut(&mut self, e: &mut syn::ExprPath) {
        if e.qself.is_none()
            && e.path.segments.len() == 1
            && e.path.segments[0].arguments.is_none()
            && let Some(r) = self.renamed(&e.path.segments[0].ident)
        {
            e.path.segments[0].ident = r;
        }
    }

    fn visit_macro_mut(&mut self, m: &mut syn::Macro) {
        // `debug_assert!(y > 0.0)`, `rt_printf!("{}", y)`: the locals in
        // the arguments.
        m.tokens = self.tokens(std::mem::take(&mut m.tokens));
    }

    fn visit_field_value_mut(&mut self, f: &mut syn::FieldValue) {
        // `S { y }`: the field keeps its name, its value is the local's.
        if f.colon_token.is_none() {
            f.colon_token = Some(Default::default());
        }
        syn::visit_mut::visit_field_value_mut(self, f);
    }
}
