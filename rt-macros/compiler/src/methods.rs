//! `#[rt_impl]`: methods, associated functions and associated constants of
//! a `#[rt_struct]`, `#[rt_payload]` or `#[rt_attributes]` type.
//!
//! ## How they reach a program
//! A method call `s.area()` names no item, so the program's own
//! dependencies cannot find the impl block. The struct's can: a program
//! that has a `Sphere` value names `Sphere` somewhere (a parameter, a
//! literal, a helper's signature, a field), so the struct's link in the
//! chain carries its impl. `#[rt_impl] impl Sphere { .. }` exports the
//! macro `__rt_impl_Sphere` (the impl's tokens and everything its methods
//! name, collected where the impl is written), and `#[rt_struct(impl)]`
//! makes the struct's chain collect that macro too, so `Sphere!` hands out
//! the struct, its impl and their dependencies. The struct says `(impl)`
//! because a macro cannot ask whether another exists; rt-std's marker
//! traits turn either half missing into an error naming the other
//! (`__require_impl_block`, `__require_impl_declared`). Rust resolves the
//! names; the lowering resolves a call by the receiver's type, as rustc
//! does.
//!
//! One inherent `#[rt_impl]` block per type (and one per `#[rt_trait]` it
//! implements, see `traits`). The impl's own dependencies leave out
//! its type (the struct's chain is collecting it); a method that names a
//! helper or another type whose own chain names this type back is a cycle
//! the chain cannot close (rustc then cannot find one of the macros):
//! write such a helper as an associated function of the type instead.
//!
//! ## How they lower
//! Each method or associated function is a helper named
//! `rtm_<Type>__<name>`, its receiver the first parameter: `&self` by value
//! (as any `&T` parameter), `&mut self` a `ptr<function, T>` (as any
//! `&mut T`), `self` by value (every declared type is `Copy`). An
//! associated constant `Type::NAME` is the module constant `Type__NAME`.
//! Inside the impl `Self` is the type's name. The inherent block of a
//! generic struct (`impl<T: Copy> Pair<T>`) makes each method generic over
//! the struct's parameters, then its own, instantiated per call as a
//! generic helper is (`lower::generic_structs`). The CPU keeps the impl as
//! written, each body rewritten to the GPU's integer semantics
//! ([`crate::cpu_semantics`]).

use crate::error::{Error, Errors};
use proc_macro2::Span;
use syn::spanned::Spanned;
use syn::visit_mut::VisitMut;

/// The name of the type an impl block is for, if it is a plain path.
pub fn self_name(i: &syn::ItemImpl) -> Option<String> {
    match &*i.self_ty {
        syn::Type::Path(p) if p.qself.is_none() => p.path.segments.last().map(|s| s.ident.to_string()),
        _ => None,
    }
}

/// The item name (`Item::name`) of `ty`'s impl block: no Rust item can be
/// called this.
pub fn impl_key(ty: &str) -> String {
    format!("impl {ty}")
}

/// The item name of an impl block: `impl Type`, or `impl Trait for Type`
/// for an impl of an `#[rt_trait]` (see `traits`).
pub fn impl_key_of(i: &syn::ItemImpl) -> String {
    let ty = self_name(i).unwrap_or_default();
    if let Some((_, path, _)) = &i.trait_
        && crate::traits::trait_name(i).is_none()
    {
        return format!("impl {} for {ty}", crate::operators::suffix(path, &ty));
    }
    match crate::traits::trait_name(i) {
        Some(t) => format!("impl {t} for {ty}"),
        None => impl_key(&ty),
    }
}

/// The link an impl block exports: `__rt_impl_Type`, or
/// `__rt_impl_Type__Trait` for a trait impl.
pub fn impl_macro_ident_of(i: &syn::ItemImpl, ty: &syn::Ident) -> syn::Ident {
    if let Some((_, path, _)) = &i.trait_
        && crate::traits::trait_name(i).is_none()
    {
        return crate::operators::link_ident(ty, path);
    }
    match crate::traits::trait_name(i) {
        Some(t) => crate::traits::impl_macro_ident(ty, &syn::Ident::new(&t, ty.span())),
        None => macro_ident(ty),
    }
}

/// The macro `#[rt_impl]` exports for `ty`, which `#[rt_struct(impl)]`
/// collects.
pub fn macro_ident(ty: &syn::Ident) -> syn::Ident {
    syn::Ident::new(&format!("__rt_impl_{ty}"), ty.span())
}

/// How the lowering keys a method, associated function or constant:
/// `Type::name`, which no free item's name can be.
pub fn member_key(ty: &str, name: &str) -> String {
    format!("{ty}::{name}")
}

/// The WGSL function of a method or associated function.
pub fn fn_wgsl_name(ty: &str, name: &str) -> String {
    format!("rtm_{ty}__{name}")
}

/// The WGSL constant of an associated constant (before the lowering's
/// renaming of names WGSL reserves).
pub fn const_wgsl_name(ty: &str, name: &str) -> String {
    format!("{ty}__{name}")
}

/// Rejects impl blocks the subset has no meaning for, at the part at
/// fault. The methods' bodies are checked where they are lowered.
pub fn check_impl(i: &syn::ItemImpl) -> Result<(), Errors> {
    let mut errors = Errors::default();
    let operator = crate::operators::of_impl(i).filter(|_| i.trait_.as_ref().is_some_and(|t| t.0.is_none()));
    if let Some((bang, path, _)) = &i.trait_ {
        if let Some((o, _)) = operator {
            check_operator_impl(i, o, &mut errors);
        } else if crate::traits::is_std_trait(path) {
            let name = path.segments.last().map(|s| s.ident.to_string()).unwrap_or_default();
            let instead = match name.as_str() {
                "IndexMut" => Some("WGSL functions return no references: write a method that sets the element"),
                "Shl" | "Shr" | "ShlAssign" | "ShrAssign" => Some("write the shift as a method"),
                _ => None,
            };
            if let Some(instead) = instead {
                errors.push(Error::unsupported(path.span(), &format!("an impl of std's `{name}`"), instead));
            } else {
                errors.push(Error::unsupported(
                    path.span(),
                    &format!("an impl of std's `{name}`"),
                    "ray programs implement traits declared with #[rt_trait] and std's operator traits (`Add`, \
                 `Mul`, `Neg`, `AddAssign`, `Index`, ...); write the operation as a method in an inherent \
                 `impl` block",
                ));
            }
        } else if let Some(b) = bang {
            errors.push(Error::unsupported(b.span(), "a negative impl", "implement the trait"));
        }
    }
    let generic_self = check_impl_generics(i, &mut errors);
    if let Some(u) = &i.unsafety {
        errors.push(Error::unsupported(u.span(), "an `unsafe impl`", "ray programs are safe code"));
    }
    match &*i.self_ty {
        syn::Type::Path(p)
            if p.qself.is_none() && (generic_self || p.path.segments.last().is_some_and(|s| s.arguments.is_none())) => {
        }
        other => errors.push(Error::unsupported(
            other.span(),
            "an impl for this type",
            "#[rt_impl] takes an impl of a #[rt_struct], #[rt_payload] or #[rt_attributes] type, by its name",
        )),
    }
    for item in &i.items {
        match item {
            syn::ImplItem::Fn(f) => check_method(f, &mut errors),
            syn::ImplItem::Const(c)
                if generic_self && crate::traits::const_names_params(&c.ty, &c.expr, &i.generics) =>
            {
                errors.push(Error::unsupported(
                    c.span(),
                    "an associated constant of a generic impl that names its parameters or `Self`",
                    "a WGSL constant has one type: write an associated function that returns the value \
                     (`fn zero() -> Self`)",
                ))
            }
            syn::ImplItem::Const(c) => {
                if !c.generics.params.is_empty() {
                    errors.push(Error::unsupported(c.generics.span(), "a generic constant", "use a concrete type"));
                }
            }
            syn::ImplItem::Type(t) if operator.is_some() && t.ident == "Output" && t.generics.params.is_empty() => {}
            syn::ImplItem::Type(t) => {
                errors.push(Error::unsupported(t.span(), "an associated type", "name the type itself where it is used"))
            }
            other => errors.push(Error::unsupported(
                other.span(),
                "this item in an #[rt_impl] block",
                "write methods, associated functions and associated constants",
            )),
        }
    }
    if errors.is_empty() { Ok(()) } else { Err(errors) }
}

/// The generic parameters of an impl: none, or (an inherent block or a
/// trait impl of a generic struct) the struct's own, in order:
/// `impl<T: Copy> Pair<T>`, `impl<T: Add<Output = T>> Add for Pair<T>`,
/// whose methods are instantiated per instance of the struct
/// (`lower::generic_structs`). Whether the type is `Name<params>`.
fn check_impl_generics(i: &syn::ItemImpl, errors: &mut Errors) -> bool {
    if i.generics.params.is_empty() {
        return false;
    }
    let before = errors.0.len();
    crate::lower::generics::check_params(&i.generics, errors);
    for c in i.generics.const_params() {
        errors.push(Error::unsupported(
            c.span(),
            "a const parameter of an impl",
            "a generic struct takes type parameters; write array lengths as numbers",
        ));
    }
    if errors.0.len() > before {
        return false;
    }
    let params: Vec<String> = i.generics.type_params().map(|t| t.ident.to_string()).collect();
    let args: Option<Vec<String>> = match &*i.self_ty {
        syn::Type::Path(p) if p.qself.is_none() => match &p.path.segments.last().map(|s| &s.arguments) {
            Some(syn::PathArguments::AngleBracketed(a)) => a
                .args
                .iter()
                .map(|a| match a {
                    syn::GenericArgument::Type(syn::Type::Path(t)) if t.qself.is_none() => {
                        t.path.get_ident().map(|i| i.to_string())
                    }
                    _ => None,
                })
                .collect(),
            _ => None,
        },
        _ => None,
    };
    if args.as_ref() != Some(&params) {
        let instead = match &i.trait_ {
            Some((_, path, _)) => {
                let name = path.segments.last().map(|s| s.ident.to_string()).unwrap_or_default();
                format!(
                    "a generic impl of a trait is for a generic struct, its parameters in the struct's order \
                     (`impl<{0}> {name} for Pair<{0}>`); implement the trait for each other type by name (`impl \
                     {name} for Disc`)",
                    params.join(", ")
                )
            }
            None => format!(
                "a generic impl is the inherent block of a generic struct, its parameters in the struct's order: \
                 `impl<{0}> Type<{0}>`; write methods for one instance (`impl Pair<f32>`) as generic code instead",
                params.join(", ")
            ),
        };
        errors.push(Error::unsupported(i.self_ty.span(), "a generic impl of this type", &instead));
        return false;
    }
    // An operator's right-hand type is a key its impl is chosen by (the
    // type itself, or one type): it cannot vary with the instance.
    if let Some((_, Some(rhs))) = crate::operators::of_impl(i) {
        let ps: Vec<crate::lower::generics::Param> = params
            .iter()
            .map(|p| crate::lower::generics::Param { name: p.clone(), kind: crate::lower::generics::ParamKind::Type })
            .collect();
        if crate::lower::generics::mentions(&rhs, &ps) {
            errors.push(Error::unsupported(
                rhs.span(),
                "an operator's right-hand type that names the impl's parameters",
                "write the right side as one type (`Mul<f32>`) or as the struct itself (`Add for Pair<T>`)",
            ));
        }
    }
    true
}

/// An impl of an operator trait: for a type of the user's, and its
/// method with the trait's receiver.
fn check_operator_impl(i: &syn::ItemImpl, o: &crate::operators::Operator, errors: &mut Errors) {
    if self_name(i).is_some_and(|n| crate::operators::is_builtin_type(&n)) {
        errors.push(Error::unsupported(
            i.self_ty.span(),
            &format!("an impl of `{}` for a built-in type", o.trait_name),
            "implement the operator on your own type, with the built-in type on the right (`impl Mul<f32> for \
             Rgb` for `c * 2.0`)",
        ));
    }
}

fn check_method(f: &syn::ImplItemFn, errors: &mut Errors) {
    let sig = &f.sig;
    // A generic method is instantiated per call, as a generic helper is
    // (`lower/generics.rs`).
    crate::lower::generics::check_params(&sig.generics, errors);
    if let Some(a) = &sig.asyncness {
        errors.push(Error::unsupported(a.span(), "an `async` method", "ray programs are synchronous"));
    }
    if let Some(u) = &sig.unsafety {
        errors.push(Error::unsupported(u.span(), "an `unsafe` method", "ray programs are safe code"));
    }
    if let Some(c) = &sig.constness {
        errors.push(Error::unsupported(
            c.span(),
            "a `const fn`",
            "drop `const`: WGSL evaluates the call at run time (an associated `const` is a constant)",
        ));
    }
    if let Some(v) = &sig.variadic {
        errors.push(Error::unsupported(v.span(), "a variadic method", "take a fixed list of parameters"));
    }
    if let Some(r) = receiver(sig)
        && r.colon_token.is_some()
    {
        let plain = matches!(&*r.ty, syn::Type::Path(p) if p.path.is_ident("Self"))
            || matches!(&*r.ty, syn::Type::Reference(t) if matches!(&*t.elem, syn::Type::Path(p) if p.path.is_ident("Self")));
        if !plain {
            errors.push(Error::unsupported(r.ty.span(), "this `self` type", "take `self`, `&self` or `&mut self`"));
        }
    }
    // The CPU copy turns `.abs()`, `.clamp(lo, hi)`, `.unwrap()` and
    // `.expect(msg)` into calls of `rt_std::arith` (see `cpu_semantics`),
    // which would not reach a user method of those names.
    let args = sig.inputs.iter().filter(|i| matches!(i, syn::FnArg::Typed(_))).count();
    let name = sig.ident.to_string();
    let taken = match name.as_str() {
        "abs" => receiver(sig).is_some() && args == 0,
        "clamp" => receiver(sig).is_some() && args == 2,
        _ => receiver(sig).is_some() && crate::cpu_semantics::unwrap_method(&name, args),
    };
    if taken {
        errors.push(Error::new(
            sig.ident.span(),
            format!(
                "a method named `{}` with this signature is not supported: the CPU copy of ray programs \
                 calls rt_std's own `{}` for it (which does what the GPU does); rename the method",
                sig.ident, sig.ident
            ),
        ));
    }
}

fn receiver(sig: &syn::Signature) -> Option<&syn::Receiver> {
    sig.inputs.iter().find_map(|i| match i {
        syn::FnArg::Receiver(r) => Some(r),
        _ => None,
    })
}

/// A method or associated function as the lowering takes it: a helper.
pub struct MethodFn {
    /// `Type::name` ([`member_key`]).
    pub key: String,
    pub wgsl_name: String,
    /// Takes `self` in some form (callable as `value.name(..)`).
    pub has_receiver: bool,
    /// The function with `Self` spelled as the type and the receiver a
    /// parameter named `self`.
    pub f: syn::ItemFn,
}

/// An associated constant as the lowering takes it.
pub struct MethodConst {
    pub key: String,
    pub wgsl_name: String,
    pub c: syn::ItemConst,
}

/// The impl's functions and constants, ready to lower like helpers and
/// `#[rt_const]`s. An impl that [`check_impl`] rejects has none (its
/// attribute reported why): the keys it would have are returned as the
/// third element, so that uses of them stay silent.
pub fn lowerable(i: &syn::ItemImpl) -> (Vec<MethodFn>, Vec<MethodConst>, Vec<String>) {
    let Some(ty) = self_name(i) else { return (Vec::new(), Vec::new(), Vec::new()) };
    if check_impl(i).is_err() {
        let keys = i
            .items
            .iter()
            .filter_map(|it| match it {
                syn::ImplItem::Fn(f) if crate::operators::of_impl(i).is_some() => {
                    Some(crate::operators::key_prefix(&ty, &f.sig.ident.to_string()))
                }
                syn::ImplItem::Fn(f) => Some(member_key(&ty, &f.sig.ident.to_string())),
                syn::ImplItem::Const(c) => Some(member_key(&ty, &c.ident.to_string())),
                _ => None,
            })
            .collect();
        return (Vec::new(), Vec::new(), keys);
    }
    let mut i = i.clone();
    let operator = crate::operators::of_impl(&i);
    if operator.is_some() {
        crate::operators::prepare_impl(&mut i);
    }
    SelfToType::of(&i).expect("checked by check_impl").visit_item_impl_mut(&mut i);
    let impl_generics = i.generics.clone();
    let mut fns = Vec::new();
    let mut consts = Vec::new();
    for item in i.items {
        match item {
            syn::ImplItem::Fn(f) => {
                let name = f.sig.ident.to_string();
                let mut sig = f.sig;
                // A generic impl's parameters come first (the instance's
                // arguments are the struct's, then the method's own).
                sig.generics = with_impl_generics(&impl_generics, &sig.generics);
                let mut has_receiver = false;
                for input in sig.inputs.iter_mut() {
                    if let syn::FnArg::Receiver(r) = input {
                        has_receiver = true;
                        *input = syn::FnArg::Typed(receiver_param(r));
                    }
                }
                let (key, wgsl_name) = match &operator {
                    Some((o, rhs)) => {
                        let rhs = match (o.kind, rhs) {
                            (crate::operators::OpKind::Unary, _) => String::new(),
                            (_, Some(r)) => crate::operators::mangle(r),
                            (_, None) => ty.clone(),
                        };
                        (crate::operators::key(&ty, &name, &rhs), crate::operators::wgsl_name(&ty, &name, &rhs))
                    }
                    None => (member_key(&ty, &name), fn_wgsl_name(&ty, &name)),
                };
                fns.push(MethodFn {
                    key,
                    wgsl_name,
                    has_receiver,
                    f: syn::ItemFn { attrs: f.attrs, vis: f.vis, sig, block: Box::new(f.block) },
                });
            }
            syn::ImplItem::Const(c) => {
                let name = c.ident.to_string();
                consts.push(MethodConst {
                    key: member_key(&ty, &name),
                    wgsl_name: const_wgsl_name(&ty, &name),
                    c: syn::ItemConst {
                        attrs: c.attrs,
                        vis: c.vis,
                        const_token: c.const_token,
                        ident: c.ident,
                        generics: c.generics,
                        colon_token: c.colon_token,
                        ty: Box::new(c.ty),
                        eq_token: c.eq_token,
                        expr: Box::new(c.expr),
                        semi_token: c.semi_token,
                    },
                });
            }
            _ => unreachable!("checked by check_impl"),
        }
    }
    (fns, consts, Vec::new())
}

/// `self`, `&self`, `&mut self` (`Self` already the type's name) as the
/// parameter `self: T`, `self: &T`, `self: &mut T`.
fn receiver_param(r: &syn::Receiver) -> syn::PatType {
    let span = r.self_token.span;
    let mutability = if r.reference.is_none() { r.mutability } else { None };
    syn::PatType {
        attrs: Vec::new(),
        pat: Box::new(syn::Pat::Ident(syn::PatIdent {
            attrs: Vec::new(),
            by_ref: None,
            mutability,
            ident: syn::Ident::new("self", span),
            subpat: None,
        })),
        colon_token: syn::Token![:](span),
        ty: r.ty.clone(),
    }
}

/// `impl`'s generic parameters, then `own`'s (a method of a generic
/// impl, as the lowering instantiates it), with both where clauses.
fn with_impl_generics(impl_generics: &syn::Generics, own: &syn::Generics) -> syn::Generics {
    if impl_generics.params.is_empty() {
        return own.clone();
    }
    let mut g = impl_generics.clone();
    g.params.extend(own.params.iter().cloned());
    if let Some(w) = &own.where_clause {
        g.make_where_clause().predicates.extend(w.predicates.iter().cloned());
    }
    g
}

/// Spells `Self` as the type: a type `Self` as the impl's type as written
/// (`Pair<T>`), a path `Self::new`, `Self { .. }` by the type's name, at
/// `Self`'s span.
#[derive(Clone)]
pub struct SelfToType {
    ident: syn::Ident,
    ty: syn::Type,
}

impl SelfToType {
    /// For `i`'s `Self`; `None` where its type is not a plain path.
    pub fn of(i: &syn::ItemImpl) -> Option<SelfToType> {
        match &*i.self_ty {
            syn::Type::Path(p) if p.qself.is_none() => {
                let ident = p.path.segments.last()?.ident.clone();
                Some(SelfToType { ident, ty: (*i.self_ty).clone() })
            }
            _ => None,
        }
    }

    /// The type's name.
    pub fn ident(&self) -> &syn::Ident {
        &self.ident
    }

    /// `b` with its `Self` spelled as the type.
    pub fn apply(&self, b: &mut syn::Block) {
        self.clone().visit_block_mut(b);
    }
}

impl VisitMut for SelfToType {
    fn visit_type_mut(&mut self, t: &mut syn::Type) {
        if let syn::Type::Path(p) = t
            && p.qself.is_none()
            && p.path.is_ident("Self")
        {
            let span = p.path.segments[0].ident.span();
            let mut ty = self.ty.clone();
            if let syn::Type::Path(tp) = &mut ty
                && let Some(last) = tp.path.segments.last_mut()
            {
                last.ident = syn::Ident::new(&last.ident.to_string(), span);
            }
            *t = ty;
            return;
        }
        syn::visit_mut::visit_type_mut(self, t);
    }

    fn visit_path_mut(&mut self, p: &mut syn::Path) {
        if let Some(first) = p.segments.first_mut()
            && first.ident == "Self"
        {
            first.ident = syn::Ident::new(&self.ident.to_string(), first.ident.span());
        }
        syn::visit_mut::visit_path_mut(self, p);
    }
}

/// The impl as the CPU compiles it: the user's, each body rewritten to
/// the GPU's integer semantics.
pub fn cpu_impl(i: &syn::ItemImpl) -> syn::ItemImpl {
    let mut i = i.clone();
    if !i.generics.params.is_empty() {
        // A generic struct's block is left as written, as a generic
        // function is (`cpu_semantics`): its bounds name std's operator
        // traits, not `rt_std::arith`'s.
        return i;
    }
    for item in i.items.iter_mut() {
        if let syn::ImplItem::Fn(m) = item {
            let mut f = syn::ItemFn {
                attrs: std::mem::take(&mut m.attrs),
                vis: m.vis.clone(),
                sig: m.sig.clone(),
                block: Box::new(m.block.clone()),
            };
            crate::cpu_semantics::rewrite_fn(&mut f);
            m.attrs = f.attrs;
            m.block = *f.block;
        }
    }
    i
}

/// Where an error about the impl as a whole points: its type.
pub fn span(i: &syn::ItemImpl) -> Span {
    i.self_ty.span()
}
