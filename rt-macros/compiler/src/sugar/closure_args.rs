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
//! An `#[rt_impl]` method given a closure is inlined the same way, its
//! `self` bound to the receiver and `Self` written as its type: called by
//! path (`Span::sample(&s, |v| ..)`, `Self::sample(self, ..)` in another
//! method of the type), or by name (`s.sample(|v| ..)`) where no other
//! type's method and no std method has that name (the rewrite runs before
//! types are known). `&mut self` is refused: the block binds a copy.
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

/// Methods of std's types that take closures (`Option`'s, iterators',
/// glam's `map`): a user's method of the same name is inlined only where
/// it is called by path, which names its type.
const STD_CLOSURE_METHODS: &[&str] = &[
    "map",
    "and_then",
    "filter",
    "unwrap_or_else",
    "or_else",
    "is_some_and",
    "is_none_or",
    "map_or",
    "map_or_else",
    "fold",
    "any",
    "all",
    "for_each",
    "filter_map",
    "find",
    "position",
    "take_while",
    "skip_while",
    "inspect",
    "max_by",
    "min_by",
    "max_by_key",
    "min_by_key",
    "zip",
    "then",
];

/// A helper or method that takes a closure, with whether each of its
/// parameters (the receiver first, for a method) is a closure; a method
/// as a function, with the type its block is for.
struct Taker {
    f: syn::ItemFn,
    roles: Vec<bool>,
    /// A method's type, which its `Self` stands for.
    owner: Option<crate::methods::SelfToType>,
    /// The type parameters of a generic block (`impl<T> Pair<T>`).
    owner_params: Vec<String>,
}

/// The helpers and methods that take a closure (shared: a block that
/// declares more extends a copy): helpers by name, methods by
/// `Type::name`, and for each method name every method so called, `None`
/// for one that takes no closure (a call by that name alone is inlined
/// only where one method has it).
#[derive(Clone, Default)]
pub struct ClosureHelpers {
    fns: HashMap<String, Rc<Taker>>,
    methods: HashMap<String, Rc<Taker>>,
    by_method: HashMap<String, Vec<Option<Rc<Taker>>>>,
}

impl ClosureHelpers {
    /// Those among `fns` and the methods of `impls`.
    pub fn new<'a>(
        fns: impl Iterator<Item = &'a syn::ItemFn>,
        impls: impl Iterator<Item = &'a syn::ItemImpl>,
    ) -> ClosureHelpers {
        let mut h = ClosureHelpers::default();
        h.extend(fns);
        for i in impls {
            let owner_params: Vec<String> = i.generics.type_params().map(|t| t.ident.to_string()).collect();
            for it in &i.items {
                let syn::ImplItem::Fn(m) = it else { continue };
                let taker = match crate::methods::SelfToType::of(i) {
                    Some(owner) if takes_closure(&m.sig) => {
                        let f = syn::ItemFn {
                            attrs: Vec::new(),
                            vis: syn::Visibility::Inherited,
                            sig: m.sig.clone(),
                            block: Box::new(m.block.clone()),
                        };
                        let roles = f.sig.inputs.iter().map(|a| is_closure_param(&f.sig, a)).collect();
                        let key = format!("{}::{}", owner.ident(), m.sig.ident);
                        let owner_params = owner_params.clone();
                        let t = Rc::new(Taker { f, roles, owner: Some(owner), owner_params });
                        h.methods.insert(key, t.clone());
                        Some(t)
                    }
                    _ => None,
                };
                h.by_method.entry(m.sig.ident.to_string()).or_default().push(taker);
            }
        }
        h
    }

    fn extend<'a>(&mut self, fns: impl Iterator<Item = &'a syn::ItemFn>) {
        for f in fns {
            let roles: Vec<bool> = f.sig.inputs.iter().map(|a| is_closure_param(&f.sig, a)).collect();
            if roles.iter().any(|r| *r) {
                self.fns.insert(
                    f.sig.ident.to_string(),
                    Rc::new(Taker { f: f.clone(), roles, owner: None, owner_params: Vec::new() }),
                );
            }
        }
    }

    /// Inlines, in `b`, each call of one of these helpers or methods or of
    /// the helpers a block declares; `owner` is the type whose method `b`
    /// is (what `Self::` names), `next` numbers the inlined calls of the
    /// unit.
    pub fn inline(&self, b: &mut syn::Block, owner: Option<&str>, next: &mut u32, errors: &mut Errors) {
        let owner = owner.map(str::to_string);
        let mut v = Inliner { helpers: self.clone(), owner, next: *next, depth: 0, errors };
        v.visit_block_mut(b);
        *next = v.next;
    }
}

/// Whether `sig` has a parameter of a closure's type ([`is_closure_param`]).
pub fn takes_closure(sig: &syn::Signature) -> bool {
    sig.inputs.iter().any(|a| is_closure_param(sig, a))
}

/// Whether `arg` of `sig` has a closure's type: `impl Fn(..)` (or `FnMut`,
/// `FnOnce`), or a type parameter bounded by one.
pub fn is_closure_param(sig: &syn::Signature, arg: &syn::FnArg) -> bool {
    let syn::FnArg::Typed(pt) = arg else { return false };
    let is_fn_bound = |b: &syn::TypeParamBound| {
        matches!(b, syn::TypeParamBound::Trait(t)
            if t.path.segments.last().is_some_and(|s| matches!(s.ident.to_string().as_str(), "Fn" | "FnMut" | "FnOnce")))
    };
    match &*pt.ty {
        syn::Type::ImplTrait(it) => it.bounds.iter().any(is_fn_bound),
        syn::Type::Path(p) if p.qself.is_none() && p.path.segments.len() == 1 => {
            let name = &p.path.segments[0].ident;
            let in_params = sig.generics.type_params().any(|tp| tp.ident == *name && tp.bounds.iter().any(is_fn_bound));
            let in_where = sig.generics.where_clause.iter().flat_map(|w| &w.predicates).any(|pr| {
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
    /// The type whose method is being rewritten.
    owner: Option<String>,
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
                syn::Stmt::Item(syn::Item::Fn(f)) if takes_closure(&f.sig) => Some(f),
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
        let Some((taker, args)) = self.taker_of(e) else { return };
        let span = e.span();
        match self.inlined(&taker, &args) {
            Ok(mut block) => {
                self.depth += 1;
                if self.depth > MAX_DEPTH {
                    self.errors.0.push(Error::new(
                        span,
                        format!(
                            "`{}` is given closures through helpers given closures too deep to inline",
                            taker.f.sig.ident
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
    /// The helper or method `e` calls, if it takes a closure, and the
    /// arguments of its parameters (the receiver first).
    fn taker_of(&mut self, e: &syn::Expr) -> Option<(Rc<Taker>, Vec<syn::Expr>)> {
        let (taker, args): (Rc<Taker>, Vec<syn::Expr>) = match e {
            syn::Expr::Call(call) => {
                let syn::Expr::Path(p) = &*call.func else { return None };
                if p.qself.is_some() {
                    return None;
                }
                let segs: Vec<String> = p.path.segments.iter().map(|s| s.ident.to_string()).collect();
                let taker = match &segs[..] {
                    [name] => self.helpers.fns.get(name)?,
                    [owner, name] => {
                        let owner = if owner == "Self" { self.owner.as_ref()? } else { owner };
                        self.helpers.methods.get(&format!("{owner}::{name}"))?
                    }
                    _ => return None,
                };
                (taker.clone(), call.args.iter().cloned().collect())
            }
            syn::Expr::MethodCall(m) => {
                let name = m.method.to_string();
                let all = self.helpers.by_method.get(&name)?;
                let taker = all.iter().flatten().next()?;
                if all.len() > 1 || STD_CLOSURE_METHODS.contains(&name.as_str()) {
                    if m.args.iter().any(|a| matches!(unparen(a), syn::Expr::Closure(_))) {
                        let owner = taker.owner.as_ref().map(|o| o.ident().to_string()).unwrap_or_default();
                        self.errors.0.push(Error::new(
                            m.method.span(),
                            format!(
                                "a method given a closure is inlined where it is called, and `{name}` may be \
                                 {}: call it by its path, `{owner}::{name}(&value, ..)`",
                                if all.len() > 1 { "more than one type's method" } else { "std's method too" }
                            ),
                        ));
                    }
                    return None;
                }
                if !matches!(taker.f.sig.inputs.first(), Some(syn::FnArg::Receiver(_))) {
                    return None; // rustc's error
                }
                let args = std::iter::once((*m.receiver).clone()).chain(m.args.iter().cloned()).collect();
                (taker.clone(), args)
            }
            _ => return None,
        };
        // A different count is rustc's error.
        (taker.roles.len() == args.len()).then_some((taker, args))
    }

    /// The block a call of `taker` with `args` stands for (see the
    /// module's doc).
    fn inlined(&mut self, taker: &Taker, args: &[syn::Expr]) -> Result<syn::Block, Error> {
        let helper = &taker.f;
        let name = &helper.sig.ident;
        let refuse = |span: proc_macro2::Span, what: &str| {
            Error::new(span, format!("`{name}` is given a closure, so it is inlined where it is called, and {what}"))
        };
        self.next += 1;
        let suffix = format!("_rt_inl{}", self.next);
        let mut body = (*helper.block).clone();
        // A method's `Self`: its type (a type parameter it names is then
        // treated as the method's own are).
        if let Some(owner) = &taker.owner {
            owner.apply(&mut body);
        }
        let mut type_params: HashSet<String> = helper.sig.generics.type_params().map(|t| t.ident.to_string()).collect();
        type_params.extend(taker.owner_params.iter().cloned());
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
        for ((input, is_closure), arg) in helper.sig.inputs.iter().zip(&taker.roles).zip(args) {
            let (ident, mutability, arg) = match input {
                syn::FnArg::Receiver(r) => {
                    if r.reference.is_some() && r.mutability.is_some() {
                        return Err(refuse(r.span(), "it takes `&mut self`: take `self` and return the new value"));
                    }
                    // `Type::m(&v, ..)`: the receiver's value.
                    let arg = match unparen(arg) {
                        syn::Expr::Reference(r) if r.mutability.is_none() => (*r.expr).clone(),
                        other => other.clone(),
                    };
                    let m = if r.reference.is_none() { r.mutability } else { None };
                    (syn::Ident::new("self", r.self_token.span), m, arg)
                }
                syn::FnArg::Typed(pt) => {
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
                                "a closure given to `{name}` is inlined where it is written: pass the closure \
                                 itself here (`{name}(|..| .., ..)`), not a name bound to one"
                            ),
                        ));
                    }
                    (pi.ident.clone(), pi.mutability, arg.clone())
                }
            };
            names.insert(ident.to_string());
            let ident = syn::Ident::new(&format!("{ident}{suffix}"), ident.span());
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
