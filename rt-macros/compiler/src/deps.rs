//! Which user items an item mentions: the paths of `#[rt_struct]`s,
//! `#[rt_function]`s and `#[rt_const]`s the macro must collect before it can
//! lower the item (see `expand` for how they are collected).

use crate::kinds;
use crate::types;
use std::collections::BTreeSet;
use syn::visit::Visit;

/// Where an item names a dependency, which says what the dependency is
/// whatever its spelling (`RGB` may be a struct, `Scale` a constant).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepKind {
    /// A type: in a type, a struct literal, or before `::` (`Kind::Metal`,
    /// `Sphere::UNIT`, `Rgb::new()`).
    Type,
    /// A constant: a path in an expression.
    Value,
    /// A function: the callee of a call.
    Function,
    /// A trait: the one an `#[rt_impl]` implements (an `#[rt_trait]`,
    /// whose link hands out its default methods).
    Trait,
}

/// A dependency: its path and what the use says it is.
#[derive(Clone, Debug)]
pub struct Dep {
    pub path: syn::Path,
    pub kind: DepKind,
}

/// The paths of `deps`, in order: the links of the chain (see `expand`).
pub fn paths(deps: &[Dep]) -> Vec<syn::Path> {
    deps.iter().map(|d| d.path.clone()).collect()
}

/// Dependency paths of an item, deduplicated, in first-seen order.
#[derive(Default)]
pub struct Deps {
    pub deps: Vec<Dep>,
    seen: BTreeSet<String>,
    locals: BTreeSet<String>,
    self_name: String,
}

impl Deps {
    fn add(&mut self, path: &syn::Path, kind: DepKind) {
        let mut p = path.clone();
        for seg in p.segments.iter_mut() {
            seg.arguments = syn::PathArguments::None;
        }
        let first = p.segments.first().map(|s| s.ident.to_string()).unwrap_or_default();
        // `Self::Output`, `Self::NAME`: the impl's own.
        if matches!(first.as_str(), "rt_std" | "std" | "core" | "glam" | "Self") {
            return;
        }
        let last = p.segments.last().map(|s| s.ident.to_string()).unwrap_or_default();
        if last == self.self_name {
            return;
        }
        let key = quote::quote!(#p).to_string();
        if self.seen.insert(key) {
            self.deps.push(Dep { path: p, kind });
        }
    }
}

fn is_builtin_type_name(name: &str) -> bool {
    types::builtin_type(name).is_some()
        || types::buffer_kind(name).is_some()
        || types::unsupported_type_advice(name).is_some()
        || name == "Self"
        // `Default::default()`, the base of a struct update.
        || name == "Default"
        || name == "Callable"
        || name == "Option"
        || types::bindless_kind(name).is_some()
        || name == types::BINDLESS_SAMPLER
}

fn is_builtin_fn(name: &str) -> bool {
    kinds::intrinsic(name).is_some()
        || matches!(
            name,
            "vec2"
                | "vec3"
                | "vec4"
                | "ivec2"
                | "ivec3"
                | "ivec4"
                | "uvec2"
                | "uvec3"
                | "uvec4"
                | "bvec2"
                | "bvec3"
                | "bvec4"
                | "reflect"
                | "refract"
                | "faceforward"
                | "smoothstep"
                | "mix"
                | "step"
                | "saturate"
        )
}

/// A name that starts with a capital: in an expression, a constant's
/// (`SCALE`, or `Scale` against the convention); before `::`, a type's
/// (`RGB::new()`, `Kind::Metal`).
fn is_capitalised(name: &str) -> bool {
    name.chars().next().is_some_and(|c| c.is_ascii_uppercase())
}

/// The capitalised names a program's expressions use that rt-std declares:
/// the transform kinds of the prelude, and `Option`'s variants.
fn is_builtin_value(name: &str) -> bool {
    matches!(name, "ObjectToWorld" | "WorldToObject" | "None" | "Some" | "Self")
}

fn is_builtin_const(name: &str) -> bool {
    kinds::constant(name).is_some() || kinds::F32_CONSTS.iter().any(|(n, _)| *n == name)
}

impl<'ast> Visit<'ast> for Deps {
    fn visit_type_path(&mut self, t: &'ast syn::TypePath) {
        if let Some(seg) = t.path.segments.last()
            && t.qself.is_none()
            && !is_builtin_type_name(&seg.ident.to_string())
            && !(t.path.segments.len() == 1 && self.locals.contains(&seg.ident.to_string()))
        {
            self.add(&t.path, DepKind::Type);
        }
        syn::visit::visit_type_path(self, t);
    }

    fn visit_expr_struct(&mut self, s: &'ast syn::ExprStruct) {
        if let Some(seg) = s.path.segments.last()
            && !is_builtin_type_name(&seg.ident.to_string())
            && !(s.path.segments.len() == 1 && self.locals.contains(&seg.ident.to_string()))
        {
            self.add(&s.path, DepKind::Type);
        }
        syn::visit::visit_expr_struct(self, s);
    }

    fn visit_expr_call(&mut self, c: &'ast syn::ExprCall) {
        if let syn::Expr::Path(p) = &*c.func
            && p.qself.is_none()
        {
            let segs: Vec<String> = p.path.segments.iter().map(|s| s.ident.to_string()).collect();
            if segs.len() >= 2 {
                // `Type::function()`: a user struct's `default()`.
                let owner = &segs[segs.len() - 2];
                if segs.len() == 2 && self.locals.contains(owner) {
                    // `T::default()`, `T` a type parameter.
                } else if !is_builtin_type_name(owner) && is_capitalised(owner) {
                    let mut owner_path = p.path.clone();
                    owner_path.segments.pop();
                    let owner_path = syn::Path {
                        leading_colon: owner_path.leading_colon,
                        segments: owner_path.segments.into_pairs().map(|p| p.into_value()).collect(),
                    };
                    self.add(&owner_path, DepKind::Type);
                } else if !is_builtin_type_name(owner) {
                    self.add(&p.path, DepKind::Function);
                }
            } else if is_capitalised(&segs[0]) && !is_builtin_value(&segs[0]) && !self.locals.contains(&segs[0]) {
                // `Rgb(a, b, c)`: a tuple struct's constructor.
                self.add(&p.path, DepKind::Type);
            } else if !is_builtin_fn(&segs[0]) && !is_builtin_value(&segs[0]) && !self.locals.contains(&segs[0]) {
                self.add(&p.path, DepKind::Function);
            }
            // A turbofish's types: `lerp::<Rgb>(..)`.
            for seg in &p.path.segments {
                self.visit_path_arguments(&seg.arguments);
            }
        }
        for a in &c.args {
            self.visit_expr(a);
        }
    }

    fn visit_expr_path(&mut self, p: &'ast syn::ExprPath) {
        let segs: Vec<String> = p.path.segments.iter().map(|s| s.ident.to_string()).collect();
        let last = segs.last().cloned().unwrap_or_default();
        if segs.len() == 1 {
            if is_capitalised(&last)
                && !self.locals.contains(&last)
                && !is_builtin_const(&last)
                && !is_builtin_value(&last)
            {
                self.add(&p.path, DepKind::Value);
            }
        } else {
            let owner = &segs[segs.len() - 2];
            if segs.len() == 2 && self.locals.contains(owner) {
                // `T::ZERO`, `T` a type parameter.
                return;
            }
            let of_type = is_capitalised(owner) && !is_builtin_type_name(owner) && owner != "TransformKind";
            if is_capitalised(&last) && !of_type && !is_builtin_type_name(owner) && owner != "consts" {
                self.add(&p.path, DepKind::Value);
            } else if of_type && is_capitalised(&last) {
                // `Kind::Metal`, in an expression or a pattern: an
                // `#[rt_enum]`'s variant; `Sphere::UNIT`: an `#[rt_impl]`'s
                // associated constant. The type is the dependency.
                let mut owner_path = p.path.clone();
                owner_path.segments.pop();
                let owner_path = syn::Path {
                    leading_colon: owner_path.leading_colon,
                    segments: owner_path.segments.into_pairs().map(|p| p.into_value()).collect(),
                };
                self.add(&owner_path, DepKind::Type);
            }
        }
    }

    fn visit_local(&mut self, l: &'ast syn::Local) {
        // `let f = |x| ...;` (or `let g = f;`): calls of `f` are of the
        // closure, not dependencies.
        if let syn::Pat::Ident(pi) = &l.pat
            && l.init.is_some()
        {
            self.locals.insert(pi.ident.to_string());
        }
        syn::visit::visit_local(self, l);
    }

    fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
        // A function declared in a body is not a dependency (the lowering
        // takes it as a helper; what it names is).
        self.locals.insert(f.sig.ident.to_string());
        self.locals.extend(param_names(&f.sig));
        self.locals.extend(f.sig.generics.type_params().map(|t| t.ident.to_string()));
        syn::visit::visit_item_fn(self, f);
    }

    fn visit_item_type(&mut self, t: &'ast syn::ItemType) {
        // A type alias declared in a body is not a dependency either
        // (`aliases` replaces its uses); what it stands for is.
        self.locals.insert(t.ident.to_string());
        syn::visit::visit_item_type(self, t);
    }

    fn visit_item_const(&mut self, c: &'ast syn::ItemConst) {
        // A function-local `const` is not a dependency.
        self.locals.insert(c.ident.to_string());
        syn::visit::visit_item_const(self, c);
    }

    fn visit_macro(&mut self, m: &'ast syn::Macro) {
        // `rt_printf!(fmt, args...)`: look into the arguments.
        if let Ok(args) = m.parse_body_with(syn::punctuated::Punctuated::<syn::Expr, syn::Token![,]>::parse_terminated)
        {
            for a in &args {
                self.visit_expr(a);
            }
        }
    }
}

/// Dependencies of a function (signature and body).
pub fn of_fn(f: &syn::ItemFn) -> Vec<Dep> {
    let mut d = Deps { self_name: f.sig.ident.to_string(), ..Deps::default() };
    // Collect fn-local consts first so their uses are not dependencies.
    d.visit_block(&f.block);
    let mut locals = std::mem::take(&mut d.locals);
    // Generic parameters are not items to collect (a type parameter in a
    // type, a const one in an expression).
    locals.extend(f.sig.generics.type_params().map(|t| t.ident.to_string()));
    locals.extend(f.sig.generics.const_params().map(|c| c.ident.to_string()));
    // A parameter called is a closure given to the helper, not a function.
    locals.extend(param_names(&f.sig));
    let mut d = Deps { self_name: f.sig.ident.to_string(), locals, ..Deps::default() };
    d.visit_signature(&f.sig);
    d.visit_block(&f.block);
    d.deps
}

/// The names a signature's parameters bind.
fn param_names(sig: &syn::Signature) -> Vec<String> {
    sig.inputs
        .iter()
        .filter_map(|a| match a {
            syn::FnArg::Typed(pt) => match &*pt.pat {
                syn::Pat::Ident(pi) => Some(pi.ident.to_string()),
                _ => None,
            },
            syn::FnArg::Receiver(_) => None,
        })
        .collect()
}

/// Dependencies of a struct (its field types).
pub fn of_struct(s: &syn::ItemStruct) -> Vec<Dep> {
    let mut d = Deps { self_name: s.ident.to_string(), ..Deps::default() };
    // A generic struct's parameters are not items.
    d.locals.extend(s.generics.type_params().map(|t| t.ident.to_string()));
    d.visit_fields(&s.fields);
    d.deps
}

/// Dependencies of an `#[rt_impl]` block: what its methods and constants
/// name, but not its own type (whose chain collects the impl; see
/// `methods`).
pub fn of_impl(i: &syn::ItemImpl) -> Vec<Dep> {
    let self_name = crate::methods::self_name(i).unwrap_or_default();
    let mut d = Deps { self_name: self_name.clone(), ..Deps::default() };
    if let Some((_, path, _)) = &i.trait_
        && !crate::traits::is_std_trait(path)
    {
        d.add(path, DepKind::Trait);
    }
    for item in &i.items {
        match item {
            syn::ImplItem::Fn(f) => {
                // As `of_fn`: the function's local constants first.
                let mut locals = Deps::default();
                locals.visit_block(&f.block);
                d.locals = locals.locals;
                for g in [&i.generics, &f.sig.generics] {
                    d.locals.extend(g.type_params().map(|t| t.ident.to_string()));
                    d.locals.extend(g.const_params().map(|c| c.ident.to_string()));
                }
                // A parameter called is a closure given to the method.
                d.locals.extend(param_names(&f.sig));
                d.visit_signature(&f.sig);
                d.visit_block(&f.block);
            }
            syn::ImplItem::Const(c) => {
                d.locals.clear();
                d.locals.extend(i.generics.type_params().map(|t| t.ident.to_string()));
                d.visit_type(&c.ty);
                d.visit_expr(&c.expr);
            }
            // An operator's `type Output`.
            syn::ImplItem::Type(t) => {
                d.locals.clear();
                d.locals.extend(i.generics.type_params().map(|t| t.ident.to_string()));
                d.visit_type(&t.ty);
            }
            _ => {}
        }
    }
    d.deps
}

/// Dependencies of an `#[rt_type]` alias (the type it stands for).
pub fn of_alias(t: &syn::ItemType) -> Vec<Dep> {
    let mut d = Deps { self_name: t.ident.to_string(), ..Deps::default() };
    d.locals.extend(t.generics.type_params().map(|p| p.ident.to_string()));
    d.visit_type(&t.ty);
    d.deps
}

/// Dependencies of a constant (its type and value).
pub fn of_const(c: &syn::ItemConst) -> Vec<Dep> {
    let mut d = Deps { self_name: c.ident.to_string(), ..Deps::default() };
    d.visit_type(&c.ty);
    d.visit_expr(&c.expr);
    d.deps
}

/// Dependencies of an `#[rt_trait]`: what its signatures and default
/// bodies name.
pub fn of_trait(t: &syn::ItemTrait) -> Vec<Dep> {
    let mut d = Deps { self_name: t.ident.to_string(), ..Deps::default() };
    for item in &t.items {
        match item {
            syn::TraitItem::Fn(f) => {
                let mut locals = Deps::default();
                if let Some(b) = &f.default {
                    locals.visit_block(b);
                }
                d.locals = locals.locals;
                d.visit_signature(&f.sig);
                if let Some(b) = &f.default {
                    d.visit_block(b);
                }
            }
            syn::TraitItem::Const(c) => {
                d.locals.clear();
                d.visit_type(&c.ty);
                if let Some((_, e)) = &c.default {
                    d.visit_expr(e);
                }
            }
            _ => {}
        }
    }
    d.deps
}
