//! Generic structs (`#[rt_struct] struct Pair<T> { a: T, b: T }`),
//! monomorphized per use, as generic helpers are (`generics`).
//!
//! - **Instances.** Each list of arguments a unit names the struct with
//!   (`Pair<f32>`, `Pair<Vec3>`) is a struct of its own: its fields' types
//!   are the template's with each parameter replaced by its argument
//!   (resolved, not respelled), its Rust name the instance's spelling
//!   (`Pair<f32>`, what messages say) and its WGSL name `rt_Pair__f32`
//!   ([`wgsl_name`]): the same in every unit, so the linker keeps one. An
//!   instance is built the first time the unit resolves it
//!   ([`GenericStructs::instance`]), from a type written anywhere (a
//!   parameter, a `let`, a field of another generic struct, a turbofish)
//!   or inferred for a literal (`Pair { a: 1.0, b: 2.0 }`: from the type
//!   wanted, else the fields' values, `func/generic_structs.rs`), its
//!   fields' instances first; the module declares every instance built.
//! - **Methods.** The inherent block `#[rt_impl] impl<T: Copy> Pair<T>`
//!   makes each method generic over the struct's parameters, then its own
//!   (`methods`); a call `p.sum()` on a `Pair<f32>` binds `T` from the
//!   receiver's instance and calls the method's instance, `rtm_Pair__sum__f32`.
//! - **Host data.** A `TypeLayout` is a constant with one Rust and one WGSL
//!   spelling, so a generic struct has no host layout: its `RtData` impl's
//!   layout is a constant that fails to evaluate with that message
//!   (`expand/data.rs`; it exists so that rustc adds no "mark it with
//!   `#[rt_struct]`" of its own to the error below), and an instance lives
//!   in programs and helpers (locals, arguments, results, fields of other
//!   generic structs, tuples, `Option`s) and never where the host reads or
//!   writes it (a payload, attributes, a variable, a buffer element, a
//!   field of a plain struct, a callable's signature):
//!   `resolve::host_data_error`.
//! - **The CPU copy** is the struct and its impl as written, with plain
//!   Rust generics; bounds are rustc's business there (a type that lacks
//!   one is rustc's error at the use), as for generic helpers. The struct's
//!   parameters take no bounds (they go on its impl block, as Rust's own
//!   style has it): each defaults to rt-std's hidden `__RtAnyType`, so that
//!   the check that a program's types were declared (`crate::declared`),
//!   which cannot know their arity, names the struct bare.

use super::resolve::{UserTypes, resolve_type};
use crate::StructRole;
use crate::error::{Error, Errors, Result};
use crate::types::{StructDef, Ty};
use proc_macro2::Span;
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;
use syn::spanned::Spanned;

/// What `#[rt_struct]` checks of a generic struct's declaration: type
/// parameters only, and the role of plain data (see the module's doc).
pub fn check_shape(s: &syn::ItemStruct, role: StructRole) -> std::result::Result<(), Errors> {
    let mut errors = Errors::default();
    if s.generics.params.is_empty() {
        return Ok(());
    }
    for p in &s.generics.params {
        match p {
            syn::GenericParam::Lifetime(l) => {
                errors.push(Error::unsupported(l.span(), "a lifetime parameter", "leave lifetimes out"))
            }
            syn::GenericParam::Const(c) => errors.push(Error::unsupported(
                c.span(),
                "a const parameter of a struct",
                "a generic struct takes type parameters; write array lengths as numbers",
            )),
            syn::GenericParam::Type(t) if !t.bounds.is_empty() || t.default.is_some() => {
                errors.push(Error::unsupported(
                    t.span(),
                    "a bound or default on a generic struct's parameter",
                    &format!(
                        "write the bounds on the struct's `#[rt_impl] impl<{0}: ..> {1}<{0}>` block and on the \
                         helpers that take it",
                        t.ident, s.ident
                    ),
                ));
            }
            syn::GenericParam::Type(_) => {}
        }
    }
    if let Some(w) = &s.generics.where_clause {
        errors.push(Error::unsupported(
            w.span(),
            "a `where` clause on a generic struct",
            "write the bounds on the struct's `#[rt_impl]` block and on the helpers that take it",
        ));
    }
    let what = match role {
        StructRole::Data => None,
        StructRole::Payload => Some(("a generic #[rt_payload]", "#[rt_payload]")),
        StructRole::Attributes => Some(("generic #[rt_attributes]", "#[rt_attributes]")),
    };
    if let Some((what, attr)) = what {
        errors.push(Error::unsupported(
            s.generics.span(),
            what,
            &format!(
                "the runtime stores a payload and attributes by one layout, and an instance of a generic struct has \
                 none the host shares: declare the {attr} struct with concrete fields (a generic struct may still \
                 be built and used inside the programs)"
            ),
        ));
    }
    if errors.is_empty() { Ok(()) } else { Err(errors) }
}

/// The WGSL name of the instance of `name` with `args`: `rt_Pair__f32`
/// (no user struct's WGSL name starts with `rt` without ending in `_`).
pub fn wgsl_name(name: &str, args: &[Ty]) -> String {
    let args: Vec<String> = args.iter().map(|a| super::generics::GenericArg::Type(a.clone()).mangle()).collect();
    format!("rt_{name}__{}", args.join("__"))
}

/// The instance's Rust spelling, its key: `Pair<f32>`.
pub fn key(name: &str, args: &[Ty]) -> String {
    let args: Vec<String> = args.iter().map(Ty::to_string).collect();
    format!("{name}<{}>", args.join(", "))
}

/// The generic structs of a unit and the instances built from them.
#[derive(Default)]
pub struct GenericStructs {
    /// The declarations, by name.
    pub templates: HashMap<String, Rc<syn::ItemStruct>>,
    /// The instances, in the order built (each after its fields' own).
    built: RefCell<Vec<Rc<StructDef>>>,
    /// The instances being built: one met again contains itself.
    building: RefCell<Vec<String>>,
}

impl GenericStructs {
    pub fn new(templates: HashMap<String, Rc<syn::ItemStruct>>) -> Self {
        GenericStructs { templates, ..GenericStructs::default() }
    }

    /// The type parameters of the generic struct `name`, if it is one.
    pub fn params(&self, name: &str) -> Option<Vec<String>> {
        self.templates.get(name).map(|t| t.generics.type_params().map(|p| p.ident.to_string()).collect())
    }

    /// The instances built so far, in order.
    pub fn built(&self) -> Vec<Rc<StructDef>> {
        self.built.borrow().clone()
    }

    /// The type `name` names with `args` (`None`: written without
    /// arguments), where `name` is a generic struct: its instance, built
    /// with `outer` resolving the types its fields name; `span` is the use.
    pub fn instance(&self, name: &str, args: Option<&[Ty]>, span: Span, outer: &UserTypes<'_>) -> Option<Result<Ty>> {
        let t = self.templates.get(name)?.clone();
        let params = self.params(name)?;
        let given = args.map_or(0, <[Ty]>::len);
        if given != params.len() {
            let s = |n: usize| if n == 1 { "" } else { "s" };
            return Some(Err(Error::new(
                span,
                format!(
                    "struct `{name}` takes {} generic argument{} (`{name}<{}>`), found {given}",
                    params.len(),
                    s(params.len()),
                    params.join(", ")
                ),
            )));
        }
        let args = args.unwrap_or_default();
        let key = key(name, args);
        if let Some(d) = self.built.borrow().iter().find(|d| d.name == key) {
            return Some(Ok(Ty::Struct(d.clone())));
        }
        if self.building.borrow().contains(&key) {
            return Some(Err(Error::new(t.ident.span(), format!("struct `{key}` contains itself"))));
        }
        self.building.borrow_mut().push(key.clone());
        let fields = self.fields(&t, &key, &params, args, span, outer);
        self.building.borrow_mut().pop();
        let def = Rc::new(StructDef {
            name: key,
            wgsl_name: wgsl_name(name, args),
            role: StructRole::Data,
            fields: match fields {
                Ok(f) => f,
                Err(e) => return Some(Err(e)),
            },
            span: t.ident.span(),
            generic: Some((name.to_string(), args.to_vec())),
        });
        self.built.borrow_mut().push(def.clone());
        Some(Ok(Ty::Struct(def)))
    }

    /// The fields of the instance `key` of `t`: each type with the
    /// parameters as `args`, plain data.
    fn fields(
        &self,
        t: &syn::ItemStruct,
        key: &str,
        params: &[String],
        args: &[Ty],
        span: Span,
        outer: &UserTypes<'_>,
    ) -> Result<Vec<(String, Ty)>> {
        let user = |n: &str, a: Option<&[Ty]>, sp: Span| match params.iter().position(|p| p == n) {
            Some(i) if a.is_none() => Some(Ok(args[i].clone())),
            _ => outer(n, a, sp),
        };
        let mut fields = Vec::new();
        for (i, f) in t.fields.iter().enumerate() {
            let fname = f.ident.as_ref().map_or_else(|| i.to_string(), |id| id.to_string());
            let ty = resolve_type(&f.ty, &user)?;
            if !ty.is_plain_data() {
                return Err(Error::new(
                    span,
                    format!(
                        "`{key}` has a field `{fname}` of type `{ty}`: fields are plain data{}",
                        super::resolve::store_advice(&ty)
                    ),
                ));
            }
            fields.push((fname, ty));
        }
        Ok(fields)
    }
}
