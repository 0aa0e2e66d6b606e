//! The items of a unit and their order: what the entry reaches, the
//! constants and structs in dependency order (the structs built as they
//! come), the helpers callees first, and the checks of a function's shape.

use super::order::{Graph, Order};
use super::{Entry, LParam, resolve_type, wgsl_ident};
use crate::error::{Error, Errors, Result};
use crate::types::{EnumDef, StructDef, Ty};
use crate::{Item, StructRole};
use proc_macro2::Span;
use std::collections::{HashMap, HashSet};
use std::rc::Rc;
use syn::spanned::Spanned;

/// The dependencies `entry` reaches, directly or through other dependencies
/// (callers may pass a superset, such as every item of a file).
pub(super) fn reachable(entry: &Entry<'_>, deps: &[Item]) -> Vec<Item> {
    let names_of = |deps: Vec<crate::deps::Dep>| -> Vec<String> {
        deps.iter().filter_map(|d| d.path.segments.last().map(|s| s.ident.to_string())).collect()
    };
    let mut todo = match entry {
        Entry::Program(_, f) | Entry::Helper(f) => names_of(crate::deps::of_fn(f)),
        // A struct's chain carries its impl (see `methods`).
        Entry::Struct(s) => {
            let mut names = names_of(crate::deps::of_struct(s));
            names.extend(impls_of(deps, &s.ident.to_string()));
            names
        }
        Entry::Const(c) => names_of(crate::deps::of_const(c)),
        // An enum's chain carries its impls (see `methods`).
        Entry::Enum(e) => {
            let mut names = impls_of(deps, &e.ident.to_string());
            names.push(e.ident.to_string());
            names
        }
    };
    let mut seen: HashSet<String> = HashSet::new();
    let mut out = Vec::new();
    while let Some(n) = todo.pop() {
        if !seen.insert(n.clone()) {
            continue;
        }
        if let Some(item) = deps.iter().find(|d| d.name() == n) {
            match item {
                Item::Struct(s, _) => todo.extend(impls_of(deps, &s.ident.to_string())),
                Item::Enum(e) => todo.extend(impls_of(deps, &e.ident.to_string())),
                _ => {}
            }
            todo.extend(names_of(match item {
                Item::Struct(s, _) => crate::deps::of_struct(s),
                Item::Function(f) => crate::deps::of_fn(f),
                Item::Const(c) => crate::deps::of_const(c),
                Item::Enum(_) => Vec::new(),
                Item::Impl(i) => crate::deps::of_impl(i),
                Item::Trait(t) => crate::deps::of_trait(t),
                Item::Alias(t) => crate::deps::of_alias(t),
            }));
            out.push(item.clone());
        }
    }
    // Keep the caller's order for stable output.
    out.sort_by_key(|i| deps.iter().position(|d| d.name() == i.name()));
    out
}

/// The item names of the impl blocks of type `ty` among `deps`: its
/// inherent block and its trait impls (a struct's chain carries them).
fn impls_of(deps: &[Item], ty: &str) -> Vec<String> {
    let mut names = vec![crate::methods::impl_key(ty)];
    for d in deps {
        if let Item::Impl(i) = d
            && crate::methods::self_name(i).as_deref() == Some(ty)
            && !names.contains(&d.name())
        {
            names.push(d.name());
        }
    }
    names
}

/// Rejects function shapes the subset has no use for.
pub(super) fn check_fn_shape(f: &syn::ItemFn) -> std::result::Result<(), Errors> {
    let mut errors = Errors::default();
    if let Some(a) = &f.sig.asyncness {
        errors.push(Error::unsupported(a.span(), "an `async` function", "ray programs are synchronous"));
    }
    if let Some(u) = &f.sig.unsafety {
        errors.push(Error::unsupported(u.span(), "an `unsafe` function", "ray programs are safe code"));
    }
    if let Some(v) = &f.sig.variadic {
        errors.push(Error::unsupported(v.span(), "a variadic function", "take a fixed list of parameters"));
    }
    for input in &f.sig.inputs {
        if let syn::FnArg::Receiver(r) = input {
            errors.push(Error::unsupported(r.span(), "a `self` parameter", "helpers are free functions"));
        }
        // `impl Fn(..)`: a closure, inlined with the call (`sugar`).
        if let syn::FnArg::Typed(pt) = input
            && let syn::Type::ImplTrait(t) = &*pt.ty
            && !crate::sugar::is_closure_param(&f.sig, input)
        {
            errors.push(Error::unsupported(
                t.span(),
                "an `impl Trait` parameter",
                "name a type parameter: `fn f<T: Trait>(x: T)`",
            ));
        }
    }
    if errors.is_empty() { Ok(()) } else { Err(errors) }
}

pub(super) fn lparams(f: &syn::ItemFn, tys: &[Ty]) -> Vec<LParam> {
    f.sig
        .inputs
        .iter()
        .filter_map(|i| match i {
            syn::FnArg::Typed(pt) => Some(pt),
            _ => None,
        })
        .zip(tys)
        .map(|(pt, ty)| {
            let (rust, mutable_binding) = match &*pt.pat {
                syn::Pat::Ident(pi) => (pi.ident.to_string(), pi.mutability.is_some()),
                _ => ("_".to_string(), false),
            };
            LParam { rust, ty: ty.clone(), mutable_binding, span: pt.span() }
        })
        .collect()
}

/// A function the unit lowers as a helper: a `#[rt_function]`, or a
/// method or associated function of an `#[rt_impl]` (see `methods`).
#[derive(Clone)]
pub(super) struct FnDef {
    /// What calls name it by: the helper's name, or `Type::name`.
    pub key: String,
    pub wgsl_name: String,
    /// A method (callable as `value.name(..)`), its receiver the first
    /// parameter.
    pub has_receiver: bool,
    pub f: syn::ItemFn,
    /// An instance of a generic helper: which, for its errors (see
    /// `generics`).
    pub instance: Option<String>,
}

/// A constant the unit lowers: a `#[rt_const]`, or an associated constant.
#[derive(Clone)]
pub(super) struct ConstDef {
    /// What uses name it by: the constant's name, or `Type::NAME`.
    pub key: String,
    pub wgsl_name: String,
    pub c: syn::ItemConst,
}

/// The keys of the constants an expression names: `NAME`, or `Type::NAME`
/// for an associated constant.
fn const_refs(e: &syn::Expr) -> Vec<String> {
    struct V(Vec<String>);
    impl<'ast> syn::visit::Visit<'ast> for V {
        fn visit_expr_path(&mut self, p: &'ast syn::ExprPath) {
            let segs: Vec<String> = p.path.segments.iter().map(|s| s.ident.to_string()).collect();
            if let Some(last) = segs.last() {
                self.0.push(last.clone());
                if segs.len() >= 2 {
                    self.0.push(crate::methods::member_key(&segs[segs.len() - 2], last));
                }
            }
        }
    }
    let mut v = V(Vec::new());
    syn::visit::Visit::visit_expr(&mut v, e);
    v.0
}

/// Constants in dependency order: a constant's value may name others, and
/// the macro chain collects them in the order uses were first seen. A
/// cycle is not an error here: lowering the values reports it.
pub(super) fn const_order(consts: &[ConstDef]) -> Vec<ConstDef> {
    struct Consts<'c>(&'c [ConstDef]);
    impl Graph for Consts<'_> {
        type Node = String;
        type Edge = ();
        type Error = std::convert::Infallible;
        fn deps(&mut self, n: &String) -> std::result::Result<Vec<(String, ())>, Self::Error> {
            let c = self.0.iter().find(|c| c.key == *n).unwrap();
            Ok(const_refs(&c.c.expr)
                .into_iter()
                .filter(|k| self.0.iter().any(|d| d.key == *k))
                .map(|k| (k, ()))
                .collect())
        }
        fn cycle(&mut self, _: &String, _: &String, _: &()) -> Option<Self::Error> {
            None
        }
    }
    let mut order = Order::new();
    for c in consts {
        let Ok(()) = order.visit(&mut Consts(consts), &c.key);
    }
    order.nodes.iter().map(|n| consts.iter().find(|c| c.key == *n).unwrap().clone()).collect()
}

/// A struct, or one of its fields (resolved once the field's own struct
/// dependencies are built, before the next field's are).
#[derive(Clone, PartialEq, Eq, Hash)]
pub(super) enum StructNode {
    Struct(String),
    Field(String, usize),
}

/// The structs as a graph for [`Order`]: built as the order reaches them
/// (a field's struct before the struct).
pub(super) struct StructGraph<'r, 'a> {
    raw: &'r [(&'a syn::ItemStruct, StructRole)],
    /// The structs built so far.
    pub defs: HashMap<String, Rc<StructDef>>,
    /// Fields resolved so far: `(struct, index) -> (name, type)`.
    fields: HashMap<(String, usize), (String, Ty)>,
    /// The unit's `#[rt_enum]`s, which fields may name.
    enums: &'r HashMap<String, Rc<EnumDef>>,
    /// The unit's generic structs' parameters, by name: no field names one.
    generic: HashMap<String, Vec<String>>,
}

impl<'r, 'a> StructGraph<'r, 'a> {
    pub fn new(
        raw: &'r [(&'a syn::ItemStruct, StructRole)],
        enums: &'r HashMap<String, Rc<EnumDef>>,
        generic: &super::generic_structs::GenericStructs,
    ) -> Self {
        let generic = generic.templates.keys().map(|n| (n.clone(), generic.params(n).unwrap_or_default())).collect();
        StructGraph { raw, defs: HashMap::new(), fields: HashMap::new(), enums, generic }
    }

    fn raw(&self, name: &str) -> Option<&(&'a syn::ItemStruct, StructRole)> {
        self.raw.iter().find(|(s, _)| s.ident == name)
    }

    /// A struct's fields: named, or a tuple struct's `0`, `1`, ...
    fn struct_fields(&self, name: &str) -> &'a syn::punctuated::Punctuated<syn::Field, syn::Token![,]> {
        match &self.raw(name).unwrap().0.fields {
            syn::Fields::Named(f) => &f.named,
            syn::Fields::Unnamed(f) => &f.unnamed,
            syn::Fields::Unit => unreachable!("checked on entering the struct"),
        }
    }
}

/// The identifiers in `tokens`, in order.
fn idents(tokens: proc_macro2::TokenStream, out: &mut Vec<String>) {
    for t in tokens {
        match t {
            proc_macro2::TokenTree::Ident(i) => out.push(i.to_string()),
            proc_macro2::TokenTree::Group(g) => idents(g.stream(), out),
            _ => {}
        }
    }
}

impl Graph for StructGraph<'_, '_> {
    type Node = StructNode;
    /// Whether the field names the struct in a callable's signature.
    type Edge = bool;
    type Error = Error;

    fn deps(&mut self, n: &StructNode) -> Result<Vec<(StructNode, bool)>> {
        match n {
            StructNode::Struct(name) => {
                let (s, _) = self.raw(name).unwrap();
                let n = match &s.fields {
                    syn::Fields::Named(f) => f.named.len(),
                    syn::Fields::Unnamed(f) => f.unnamed.len(),
                    syn::Fields::Unit => {
                        return Err(Error::unsupported(s.ident.span(), "a unit struct", "give it at least one field"));
                    }
                };
                Ok((0..n).map(|i| (StructNode::Field(name.clone(), i), false)).collect())
            }
            StructNode::Field(name, i) => {
                // Every struct the field's type names (nested, an array's or
                // a tuple's element, in a callable's signature) first, so
                // they are built when the field's type is resolved.
                let ty = &self.struct_fields(name)[*i].ty;
                let mut named = Vec::new();
                idents(quote::quote!(#ty), &mut named);
                let through_callable =
                    named.iter().any(|n| n == "Callable" || crate::types::bindless_kind(n).is_some());
                let mut deps: Vec<(StructNode, bool)> = Vec::new();
                for n in named {
                    let node = StructNode::Struct(n.clone());
                    if self.raw(&n).is_some() && !deps.iter().any(|(d, _)| *d == node) {
                        deps.push((node, through_callable));
                    }
                }
                Ok(deps)
            }
        }
    }

    fn done(&mut self, n: &StructNode) -> Result<()> {
        match n {
            StructNode::Field(name, i) => {
                let f = &self.struct_fields(name)[*i];
                let fname = f.ident.as_ref().map_or_else(|| i.to_string(), |id| id.to_string());
                let user = |n: &str, args: Option<&[Ty]>, span: Span| -> Option<Result<Ty>> {
                    if let Some(params) = self.generic.get(n) {
                        // A plain struct is host data, which an instance of
                        // a generic struct cannot be (`generic_structs`).
                        let args = args.map(|a| a.iter().map(Ty::to_string).collect::<Vec<_>>());
                        let shown = format!("{n}<{}>", args.unwrap_or_else(|| params.clone()).join(", "));
                        return Some(Err(Error::unsupported(
                            span,
                            &format!(
                                "a field of type `{shown}` (an instance of the generic struct `{n}`) in a struct without parameters"
                            ),
                            &format!(
                                "a struct without parameters is host data, laid out once, and a generic struct has no \
                                 layout: make `{name}` generic too (`struct {name}<T> {{ .. }}`), or declare a struct with concrete fields for the field"
                            ),
                        )));
                    }
                    if args.is_some() {
                        return None;
                    }
                    self.defs
                        .get(n)
                        .map(|d| Ok(Ty::Struct(d.clone())))
                        .or_else(|| self.enums.get(n).map(|e| Ok(Ty::Enum(e.clone()))))
                };
                let ty = resolve_type(&f.ty, &user)?;
                if !ty.is_plain_data() {
                    return Err(Error::new(
                        f.ty.span(),
                        format!(
                            "a struct field cannot be a `{ty}`: fields are plain data{}",
                            super::resolve::store_advice(&ty)
                        ),
                    ));
                }
                self.fields.insert((name.clone(), *i), (fname, ty));
            }
            StructNode::Struct(name) => {
                let (s, role) = *self.raw(name).unwrap();
                let n = self.struct_fields(name).len();
                let fields = (0..n).map(|i| self.fields[&(name.clone(), i)].clone()).collect();
                let def = Rc::new(StructDef {
                    name: name.to_string(),
                    wgsl_name: wgsl_ident(name),
                    role,
                    fields,
                    span: s.ident.span(),
                    generic: None,
                });
                self.defs.insert(name.to_string(), def);
            }
        }
        Ok(())
    }

    fn cycle(&mut self, from: &StructNode, to: &StructNode, through_callable: &bool) -> Option<Error> {
        let StructNode::Struct(name) = to else { unreachable!("a field is entered from its struct only") };
        let (s, _) = self.raw(name).unwrap();
        if let (StructNode::Field(holder, i), true) = (from, through_callable) {
            // Legal Rust (an id is one word whatever its signature), but the
            // signature's types are resolved before the struct is built.
            let f = &self.struct_fields(holder)[*i];
            let mut named = Vec::new();
            let ty = &f.ty;
            idents(quote::quote!(#ty), &mut named);
            if let Some(id) = named.iter().find(|n| crate::types::bindless_kind(n).is_some()) {
                // The same for a bindless id's element type.
                let construct = if holder == name {
                    format!("a `{id}` field whose element type is its own struct (`{name}`)")
                } else {
                    format!(
                        "a `{id}` field of `{holder}` whose element type names `{name}`, a struct holding `{holder}`"
                    )
                };
                return Some(Error::unsupported(
                    f.ty.span(),
                    &construct,
                    &format!("keep the id as a `u32` and read through `{id}::<{name}>::from_id(id)`"),
                ));
            }
            let construct = if holder == name {
                format!("a `Callable` field whose signature names its own struct (`{name}`)")
            } else {
                format!("a `Callable` field of `{holder}` whose signature names `{name}`, a struct holding `{holder}`")
            };
            return Some(Error::unsupported(
                f.ty.span(),
                &construct,
                "pass the ids in a struct the signature does not name, or as `u32`s called through \
                 `Callable::<fn(..) -> R>::from_id(id)`",
            ));
        }
        Some(Error::new(s.ident.span(), format!("struct `{name}` contains itself")))
    }
}

/// The unit's `#[rt_enum]`s by name, and the names of those whose shape
/// the subset rejects (their own macro reports why).
pub(super) fn enums(deps: &[Item]) -> (HashMap<String, Rc<EnumDef>>, HashSet<String>) {
    let mut defs = HashMap::new();
    let mut failed = HashSet::new();
    for d in deps {
        if let Item::Enum(e) = d {
            match crate::enums::check(e) {
                Ok(def) => {
                    defs.insert(def.name.clone(), Rc::new(def));
                }
                Err(_) => {
                    failed.insert(e.ident.to_string());
                }
            }
        }
    }
    (defs, failed)
}

/// The dependencies by kind, with the entry among them if it is an item.
pub(super) struct ByKind<'a> {
    pub structs: Vec<(&'a syn::ItemStruct, StructRole)>,
    /// Helpers, then the impls' methods and associated functions.
    pub fns: Vec<FnDef>,
    /// `#[rt_const]`s, then the impls' associated constants.
    pub consts: Vec<ConstDef>,
    /// Members of impls whose shape was rejected (their attribute said
    /// why): uses of them are silent errors.
    pub failed: Vec<String>,
    /// The generic helpers, by name (their instances are among `fns`).
    pub generics: HashMap<String, Rc<syn::ItemFn>>,
    /// The generic structs, by name (see `generic_structs`).
    pub generic_structs: HashMap<String, Rc<syn::ItemStruct>>,
}

/// The dependencies by kind; `instances`, of the generic helpers among
/// them, are helpers too.
pub(super) fn by_kind<'a>(
    entry: &'a Entry<'_>,
    deps: &'a [Item],
    instances: &[super::generics::Instance],
) -> ByKind<'a> {
    let mut k = ByKind {
        structs: Vec::new(),
        fns: Vec::new(),
        consts: Vec::new(),
        failed: Vec::new(),
        generics: HashMap::new(),
        generic_structs: HashMap::new(),
    };
    let helper = |f: &syn::ItemFn| FnDef {
        key: f.sig.ident.to_string(),
        wgsl_name: format!("rtf_{}", f.sig.ident),
        has_receiver: false,
        f: f.clone(),
        instance: None,
    };
    let constant = |c: &syn::ItemConst| ConstDef {
        key: c.ident.to_string(),
        wgsl_name: wgsl_ident(&c.ident.to_string()),
        c: c.clone(),
    };
    let mut impls = Vec::new();
    for d in deps {
        match d {
            Item::Struct(s, r) if !s.generics.params.is_empty() => {
                // One its attribute refused is a silent error where named.
                match super::generic_structs::check_shape(s, *r) {
                    Ok(()) => {
                        k.generic_structs.insert(s.ident.to_string(), Rc::new(s.clone()));
                    }
                    Err(_) => k.failed.push(s.ident.to_string()),
                }
            }
            Item::Struct(s, r) => k.structs.push((s, *r)),
            Item::Function(f) if super::generics::is_generic(f) => {
                k.generics.insert(f.sig.ident.to_string(), Rc::new(f.clone()));
            }
            Item::Function(f) => k.fns.push(helper(f)),
            Item::Const(c) => k.consts.push(constant(c)),
            // Built before the structs (`ModuleCtx::enums`).
            Item::Enum(_) => {}
            Item::Impl(i) => impls.push(i),
            // Through the impls that use its defaults.
            Item::Trait(_) => {}
            // Replaced by what it stands for before the lowering.
            Item::Alias(_) => {}
        }
    }
    match &entry {
        Entry::Struct(s) if !s.generics.params.is_empty() => {
            k.generic_structs.entry(s.ident.to_string()).or_insert_with(|| Rc::new((*s).clone()));
        }
        Entry::Struct(s) => {
            if !k.structs.iter().any(|(x, _)| x.ident == s.ident) {
                k.structs.push((s, StructRole::Data));
            }
        }
        Entry::Helper(f) => {
            if !k.fns.iter().any(|x| f.sig.ident == x.key) {
                k.fns.push(helper(f));
            }
        }
        Entry::Const(c) => {
            if !k.consts.iter().any(|x| c.ident == x.key) {
                k.consts.push(constant(c));
            }
        }
        Entry::Program(..) | Entry::Enum(_) => {}
    }
    impls_by_kind(&mut k, deps, impls);
    for inst in instances {
        if let Some(g) = k.generics.get(&inst.generic) {
            k.fns.push(FnDef {
                key: inst.key(),
                wgsl_name: inst.wgsl_name(),
                has_receiver: takes_self(g),
                f: super::generics::instantiate(g, &inst.args),
                instance: Some(inst.describe(g)),
            });
        }
    }
    k
}

/// Whether a method (its receiver made a parameter, `methods::lowerable`)
/// takes `self`.
fn takes_self(f: &syn::ItemFn) -> bool {
    matches!(f.sig.inputs.first(), Some(syn::FnArg::Typed(pt)) if matches!(&*pt.pat, syn::Pat::Ident(i) if i.ident == "self"))
}

/// The impls' methods, associated functions and constants into `k`; a
/// generic method among the generics, by its key (`Type::name`).
fn impls_by_kind(k: &mut ByKind<'_>, deps: &[Item], mut impls: Vec<&syn::ItemImpl>) {
    let traits: Vec<&syn::ItemTrait> = deps
        .iter()
        .filter_map(|d| match d {
            Item::Trait(t) => Some(t),
            _ => None,
        })
        .collect();
    // Inherent blocks first: where a trait impl defines a name the
    // inherent block does, a call means the inherent one, as in Rust.
    impls.sort_by_key(|i| i.trait_.is_some());
    for i in impls {
        // A trait impl with the trait's defaults it does not override.
        let of_trait = crate::traits::trait_name(i).and_then(|n| traits.iter().find(|t| t.ident == n));
        let completed = of_trait.map(|t| crate::traits::complete(i, t));
        let i = completed.as_ref().unwrap_or(i);
        let (fns, consts, failed) = crate::methods::lowerable(i);
        let taken: Vec<String> = k
            .fns
            .iter()
            .map(|f| f.key.clone())
            .chain(k.consts.iter().map(|c| c.key.clone()))
            .chain(k.generics.keys().cloned())
            .collect();
        let fns = fns.into_iter().filter(|m| !taken.contains(&m.key));
        let consts = consts.into_iter().filter(|c| !taken.contains(&c.key));
        // A method given a closure is inlined where it is called (`sugar`).
        let fns = fns.filter(|m| !crate::sugar::takes_closure(&m.f.sig));
        let (generic, fns): (Vec<_>, Vec<_>) = fns.partition(|m| super::generics::is_generic(&m.f));
        for m in generic {
            k.generics.insert(m.key, Rc::new(m.f));
        }
        k.fns.extend(fns.into_iter().map(|m| FnDef {
            key: m.key,
            wgsl_name: m.wgsl_name,
            has_receiver: m.has_receiver,
            f: m.f,
            instance: None,
        }));
        k.consts.extend(consts.into_iter().map(|c| ConstDef {
            key: c.key,
            wgsl_name: wgsl_ident(&c.wgsl_name),
            c: c.c,
        }));
        k.failed.extend(failed);
    }
}

/// Orders helpers callees-first; a cycle is recursion, which WGSL lacks (the
/// error comes with the helper whose call closes the cycle). Calls by path
/// are read from the bodies; method calls (`value.name(..)`, which only
/// the receiver's type resolves) are given in `method_calls`, by caller.
pub(super) fn helper_order(
    items: &HashMap<String, FnDef>,
    method_calls: &HashMap<String, Vec<(String, Span)>>,
) -> std::result::Result<Vec<String>, (String, Error)> {
    struct Calls<'i>(&'i HashMap<String, FnDef>, &'i HashMap<String, Vec<(String, Span)>>);
    impl Graph for Calls<'_> {
        type Node = String;
        type Edge = Span;
        type Error = (String, Error);
        fn deps(&mut self, n: &String) -> std::result::Result<Vec<(String, Span)>, Self::Error> {
            let mut found = Vec::new();
            collect_calls(&self.0[n].f.block, &mut found);
            found.extend(self.1.get(n).into_iter().flatten().cloned());
            Ok(found.into_iter().filter(|(c, _)| self.0.contains_key(c)).collect())
        }
        fn cycle(&mut self, n: &String, c: &String, span: &Span) -> Option<Self::Error> {
            let what = if n == c {
                format!("recursion (`{n}` calls itself)")
            } else {
                format!("recursion (`{n}` calls `{c}`, which leads back to `{n}`)")
            };
            Some((n.to_string(), Error::unsupported(*span, &what, "WGSL has no recursion; rewrite it as a loop")))
        }
    }
    let mut names: Vec<&String> = items.keys().collect();
    names.sort();
    let mut order = Order::new();
    for n in names {
        order.visit(&mut Calls(items, method_calls), n)?;
    }
    Ok(order.nodes)
}

/// Names of functions called in a block, with the call span: a path's
/// last segment, and for `Type::name(..)` also the associated function's
/// key (`Type::name`).
pub fn collect_calls(block: &syn::Block, out: &mut Vec<(String, Span)>) {
    struct V<'a>(&'a mut Vec<(String, Span)>);
    impl<'ast> syn::visit::Visit<'ast> for V<'_> {
        fn visit_expr_call(&mut self, c: &'ast syn::ExprCall) {
            if let syn::Expr::Path(p) = &*c.func
                && let Some(seg) = p.path.segments.last()
            {
                self.0.push((seg.ident.to_string(), c.span()));
                if p.path.segments.len() >= 2 {
                    let owner = &p.path.segments[p.path.segments.len() - 2].ident;
                    self.0.push((crate::methods::member_key(&owner.to_string(), &seg.ident.to_string()), c.span()));
                }
            }
            syn::visit::visit_expr_call(self, c);
        }
    }
    syn::visit::Visit::visit_block(&mut V(out), block);
}
