//! Lowering: a unit (one program, helper, struct or constant, plus every
//! item it depends on) to one standalone WGSL module with a source map.
//!
//! The module is laid out as four sections the runtime's linker relies on:
//! a *prelude* of runtime stubs (replaced at link time by the real runtime),
//! the *types*, the *functions* (accessors, constants and helpers) and the
//! *program*. Names: programs are `rtp_<name>`, helpers `rtf_<name>`, runtime
//! items `rt_*`/`Rt*`; user structs and constants keep their names.

pub mod accessors;
pub mod builtins;
pub mod func;
pub mod text;
pub mod value;

use crate::error::{Error, Errors, Result};
use crate::kinds::Kind;
use crate::signature::{self, Role};
use crate::types::{self, StructDef, Ty};
use crate::{Item, StructRole};
use accessors::Accessors;
use func::{FnLowerer, FnRole, LParam};
use proc_macro2::Span;
use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::rc::Rc;
use syn::spanned::Spanned;

/// A helper's signature and what its body does, as callers need it.
#[derive(Clone, Debug)]
pub struct HelperSig {
    pub name: String,
    pub wgsl_name: String,
    pub params: Vec<Ty>,
    pub ret: Ty,
    /// Kind-restricted intrinsics it calls, directly or through helpers.
    pub intrinsics: Vec<&'static str>,
    pub traced: Vec<Ty>,
    /// A helper that traces has a resumable form (`<wgsl_name>_rs`).
    pub resumable: bool,
}

#[derive(Clone, Debug)]
pub struct ConstInfo {
    pub wgsl_name: String,
    pub ty: Ty,
}

/// Module-wide state shared by the functions being lowered.
pub struct ModuleCtx {
    pub structs: HashMap<String, Rc<StructDef>>,
    pub consts: HashMap<String, ConstInfo>,
    pub helpers: HashMap<String, HelperSig>,
    pub global_names: HashSet<String>,
    spans: RefCell<Vec<Span>>,
    pub accessors: RefCell<Accessors>,
    pub trace_types: RefCell<BTreeMap<String, Ty>>,
    pub report_types: RefCell<BTreeMap<String, Ty>>,
    /// Dependencies that failed to lower: using them is a silent error.
    pub failed: HashSet<String>,
    printf: RefCell<BTreeMap<u32, (String, Vec<String>)>>,
}

impl ModuleCtx {
    pub fn span_id(&self, span: Span) -> usize {
        let mut spans = self.spans.borrow_mut();
        spans.push(span);
        spans.len() - 1
    }

    /// A stable id for a printf format: the same format and argument types
    /// get the same id in every program, so shared helpers link unchanged.
    pub fn printf_id(&self, fmt: &str, types: &[String]) -> u32 {
        let mut h: u32 = 0x811c9dc5;
        for b in fmt.bytes().chain(types.join(",").bytes()) {
            h ^= b as u32;
            h = h.wrapping_mul(0x01000193);
        }
        self.printf.borrow_mut().insert(h, (fmt.to_string(), types.to_vec()));
        h
    }

    pub fn resolve_type(&self, ty: &syn::Type) -> Result<Ty> {
        resolve_type(ty, &|name| self.structs.get(name).map(|d| Ty::Struct(d.clone()))).map_err(|e| {
            // A struct whose own declaration failed: that error is enough.
            fn mentions(ts: proc_macro2::TokenStream, names: &HashSet<String>) -> bool {
                ts.into_iter().any(|t| match t {
                    proc_macro2::TokenTree::Ident(i) => names.contains(&i.to_string()),
                    proc_macro2::TokenTree::Group(g) => mentions(g.stream(), names),
                    _ => false,
                })
            }
            if mentions(quote::quote!(#ty), &self.failed) { Error::silent(e.span) } else { e }
        })
    }
}

/// Resolves a Rust type in the subset; `user` looks up user structs.
pub fn resolve_type(ty: &syn::Type, user: &dyn Fn(&str) -> Option<Ty>) -> Result<Ty> {
    match ty {
        syn::Type::Path(p) => {
            if p.qself.is_some() {
                return Err(Error::unsupported(p.span(), "a qualified type", "name the type directly"));
            }
            let seg = p.path.segments.last().unwrap();
            let name = seg.ident.to_string();
            if let Some(kind) = types::buffer_kind(&name) {
                let arg = match &seg.arguments {
                    syn::PathArguments::AngleBracketed(a) if a.args.len() == 1 => match &a.args[0] {
                        syn::GenericArgument::Type(t) => t,
                        other => return Err(Error::new(other.span(), format!("`{name}` takes an element type"))),
                    },
                    _ => return Err(Error::new(seg.span(), format!("`{name}` takes one element type: `{name}<T>`"))),
                };
                let elem = resolve_type(arg, user)?;
                if !elem.is_plain_data() {
                    return Err(Error::new(arg.span(), format!("`{elem}` cannot be a buffer element")));
                }
                return Ok(Ty::Buffer(kind, Box::new(elem)));
            }
            // Before the generic arguments: `Vec<f32>` is a heap type.
            if let Some(advice) = types::unsupported_type_advice(&name) {
                return Err(Error::unsupported(seg.ident.span(), &format!("the type `{name}`"), advice));
            }
            if !seg.arguments.is_none() {
                return Err(Error::unsupported(seg.arguments.span(), "generic type arguments", "use concrete types"));
            }
            if let Some(t) = types::builtin_type(&name) {
                return Ok(t);
            }
            if let Some(t) = user(&name) {
                return Ok(t);
            }
            if name == "Self" {
                return Err(Error::unsupported(p.span(), "`Self`", "name the type"));
            }
            Err(Error::new(
                p.span(),
                format!(
                    "cannot find type `{name}` in ray programs: declare it with #[rt_struct], #[rt_payload] or #[rt_attributes]"
                ),
            ))
        }
        syn::Type::Array(a) => {
            let elem = resolve_type(&a.elem, user)?;
            let n = func::array_len(&a.len)?;
            Ok(Ty::Array(Box::new(elem), n))
        }
        syn::Type::Reference(r) => {
            if r.lifetime.is_some() {
                return Err(Error::unsupported(r.span(), "a lifetime", "leave lifetimes out"));
            }
            Ok(Ty::Ref(r.mutability.is_some(), Box::new(resolve_type(&r.elem, user)?)))
        }
        syn::Type::Tuple(t) if t.elems.is_empty() => Ok(Ty::Unit),
        syn::Type::Tuple(t) => {
            Err(Error::unsupported(t.span(), "a tuple type", "use a struct declared with #[rt_struct]"))
        }
        syn::Type::Paren(p) => resolve_type(&p.elem, user),
        syn::Type::Slice(s) => {
            Err(Error::unsupported(s.span(), "a slice", "use a fixed-size array or a buffer variable"))
        }
        syn::Type::Ptr(p) => Err(Error::unsupported(p.span(), "a raw pointer", "use `&mut` parameters")),
        syn::Type::TraitObject(t) => {
            Err(Error::unsupported(t.span(), "a trait object", "WGSL has no dynamic dispatch; take a concrete type"))
        }
        syn::Type::ImplTrait(t) => Err(Error::unsupported(t.span(), "`impl Trait`", "use concrete types")),
        syn::Type::BareFn(f) => {
            Err(Error::unsupported(f.span(), "a function pointer", "WGSL has no function pointers"))
        }
        syn::Type::Never(n) => Err(Error::unsupported(n.span(), "the never type", "return a value")),
        other => {
            Err(Error::unsupported(other.span(), "this type", "use scalars, glam types, arrays and #[rt_struct]s"))
        }
    }
}

/// WGSL reserved words and the builtin names our output uses; identifiers
/// from Rust that collide get a trailing `_`.
pub fn is_reserved(name: &str) -> bool {
    const EXTRA: &[&str] = &[
        "vec2",
        "vec3",
        "vec4",
        "mat2x2",
        "mat3x3",
        "mat4x4",
        "array",
        "bool",
        "f32",
        "i32",
        "u32",
        "ptr",
        "atomic",
        "sampler",
        "texture_2d",
        "abs",
        "acos",
        "acosh",
        "all",
        "any",
        "asin",
        "asinh",
        "atan",
        "atan2",
        "atanh",
        "bitcast",
        "ceil",
        "clamp",
        "cos",
        "cosh",
        "countLeadingZeros",
        "countOneBits",
        "countTrailingZeros",
        "cross",
        "degrees",
        "determinant",
        "distance",
        "dot",
        "exp",
        "exp2",
        "faceForward",
        "floor",
        "fma",
        "fract",
        "inverseSqrt",
        "length",
        "log",
        "log2",
        "max",
        "min",
        "mix",
        "normalize",
        "pow",
        "radians",
        "reflect",
        "refract",
        "reverseBits",
        "round",
        "saturate",
        "select",
        "sign",
        "sin",
        "sinh",
        "smoothstep",
        "sqrt",
        "step",
        "tan",
        "tanh",
        "transpose",
        "trunc",
    ];
    naga::keywords::wgsl::RESERVED.contains(&name) || EXTRA.contains(&name)
}

/// The WGSL name of a struct field or module-level identifier.
pub fn wgsl_ident(name: &str) -> String {
    if is_reserved(name) || name.starts_with("rt") || name.starts_with("Rt") || name.starts_with("__") {
        format!("{name}_")
    } else {
        name.to_string()
    }
}

/// What a lowered unit produced.
#[derive(Clone, Debug, Default)]
pub struct Lowered {
    pub name: String,
    pub kind: Option<Kind>,
    pub wgsl_entry: String,
    /// The whole validated module.
    pub wgsl: String,
    pub prelude: String,
    pub types: Vec<(String, String)>,
    pub functions: Vec<(String, String)>,
    pub program: String,
    pub payload: Option<Ty>,
    pub attributes: Option<Ty>,
    pub variables: Vec<(String, Ty)>,
    pub intrinsics: Vec<String>,
    pub traced: Vec<Ty>,
    /// `(id, format, argument WGSL types)`.
    pub printf: Vec<(u32, String, Vec<String>)>,
    /// A tracing program's resumable form (frame declarations and the
    /// function; see `func/resume.rs`), validated like the plain form.
    pub resumable: Option<String>,
    /// Why a tracing program has no resumable form.
    pub not_resumable: Option<String>,
    /// Resumable forms of the helpers that trace (`(name, text)`, callees
    /// first).
    pub resumable_functions: Vec<(String, String)>,
}

/// The entry being lowered.
pub enum Entry<'a> {
    Program(Kind, &'a syn::ItemFn),
    Helper(&'a syn::ItemFn),
    Struct(&'a syn::ItemStruct),
    Const(&'a syn::ItemConst),
}

/// Lowers `entry` with its dependencies `deps` into a validated module.
/// Errors in the dependencies are reported too (see [`lower_own`]).
pub fn lower(entry: Entry<'_>, deps: &[Item]) -> std::result::Result<Lowered, Errors> {
    lower_impl(entry, deps, true)
}

/// Like [`lower`], but errors inside dependencies are silent: in the macro
/// chain each dependency's own macro reports them, so a helper's mistake is
/// shown once, not again at every program that calls it.
pub fn lower_own(entry: Entry<'_>, deps: &[Item]) -> std::result::Result<Lowered, Errors> {
    lower_impl(entry, deps, false)
}

fn lower_impl(entry: Entry<'_>, deps: &[Item], report_deps: bool) -> std::result::Result<Lowered, Errors> {
    let mut errors = Errors::default();
    // Whether an item is the entry itself, and which item each error came
    // from: `(index of its first error, is the entry)`, in order.
    let owns = |name: &str| match &entry {
        Entry::Helper(f) => f.sig.ident == name,
        Entry::Struct(s) => s.ident == name,
        Entry::Const(c) => c.ident == name,
        Entry::Program(..) => false,
    };
    let mut owners: Vec<(usize, bool)> = Vec::new();
    let deps = reachable(&entry, deps);
    let mut structs_raw: Vec<(&syn::ItemStruct, StructRole)> = Vec::new();
    let mut helpers_raw: Vec<&syn::ItemFn> = Vec::new();
    let mut consts_raw: Vec<&syn::ItemConst> = Vec::new();
    for d in &deps {
        match d {
            Item::Struct(s, r) => structs_raw.push((s, *r)),
            Item::Function(f) => helpers_raw.push(f),
            Item::Const(c) => consts_raw.push(c),
        }
    }
    match &entry {
        Entry::Struct(s) => {
            if !structs_raw.iter().any(|(x, _)| x.ident == s.ident) {
                structs_raw.push((s, StructRole::Data));
            }
        }
        Entry::Helper(f) => {
            if !helpers_raw.iter().any(|x| x.sig.ident == f.sig.ident) {
                helpers_raw.push(f);
            }
        }
        Entry::Const(c) => {
            if !consts_raw.iter().any(|x| x.ident == c.ident) {
                consts_raw.push(c);
            }
        }
        Entry::Program(..) => {}
    }
    // Constants in dependency order: a constant's value may name others, and
    // the macro chain collects them in the order uses were first seen.
    let consts_raw = {
        fn visit<'a>(
            c: &'a syn::ItemConst,
            all: &[&'a syn::ItemConst],
            out: &mut Vec<&'a syn::ItemConst>,
            visiting: &mut Vec<String>,
        ) {
            let name = c.ident.to_string();
            if out.iter().any(|o| o.ident == c.ident) || visiting.contains(&name) {
                return;
            }
            visiting.push(name);
            for p in crate::deps::of_const(c) {
                if let Some(last) = p.segments.last()
                    && let Some(d) = all.iter().find(|d| d.ident == last.ident)
                {
                    visit(d, all, out, visiting);
                }
            }
            visiting.pop();
            out.push(c);
        }
        let mut ordered = Vec::with_capacity(consts_raw.len());
        for c in &consts_raw {
            visit(c, &consts_raw, &mut ordered, &mut Vec::new());
        }
        ordered
    };

    // Structs, in dependency order.
    let mut structs: HashMap<String, Rc<StructDef>> = HashMap::new();
    let mut struct_order: Vec<String> = Vec::new();
    fn build_struct(
        name: &str,
        raw: &[(&syn::ItemStruct, StructRole)],
        done: &mut HashMap<String, Rc<StructDef>>,
        order: &mut Vec<String>,
        visiting: &mut Vec<String>,
    ) -> Result<Option<Rc<StructDef>>> {
        if let Some(d) = done.get(name) {
            return Ok(Some(d.clone()));
        }
        let Some((s, role)) = raw.iter().find(|(s, _)| s.ident == name) else { return Ok(None) };
        if visiting.iter().any(|v| v == name) {
            return Err(Error::new(s.ident.span(), format!("struct `{name}` contains itself")));
        }
        visiting.push(name.to_string());
        if !s.generics.params.is_empty() {
            return Err(Error::unsupported(s.generics.span(), "a generic struct", "use concrete field types"));
        }
        let fields_named = match &s.fields {
            syn::Fields::Named(f) => f,
            syn::Fields::Unnamed(f) => {
                return Err(Error::unsupported(f.span(), "a tuple struct", "use named fields"));
            }
            syn::Fields::Unit => {
                return Err(Error::unsupported(s.ident.span(), "a unit struct", "give it at least one field"));
            }
        };
        let mut fields = Vec::new();
        for f in &fields_named.named {
            let fname = f.ident.as_ref().unwrap().to_string();
            // Resolve nested structs first so they are in `done`.
            if let syn::Type::Path(p) = &f.ty
                && let Some(seg) = p.path.segments.last()
            {
                let n = seg.ident.to_string();
                build_struct(&n, raw, done, order, visiting)?;
            }
            if let syn::Type::Array(a) = &f.ty
                && let syn::Type::Path(p) = &*a.elem
                && let Some(seg) = p.path.segments.last()
            {
                build_struct(&seg.ident.to_string(), raw, done, order, visiting)?;
            }
            let ty = resolve_type(&f.ty, &|n| done.get(n).map(|d| Ty::Struct(d.clone())))?;
            if !ty.is_plain_data() {
                return Err(Error::new(
                    f.ty.span(),
                    format!("a struct field cannot be a `{ty}`: fields are plain data"),
                ));
            }
            fields.push((fname, ty));
        }
        visiting.pop();
        let def = Rc::new(StructDef {
            name: name.to_string(),
            wgsl_name: wgsl_ident(name),
            role: *role,
            fields,
            span: s.ident.span(),
        });
        done.insert(name.to_string(), def.clone());
        order.push(name.to_string());
        Ok(Some(def))
    }
    for (s, _) in &structs_raw {
        owners.push((errors.0.len(), owns(&s.ident.to_string())));
        if let Err(e) =
            build_struct(&s.ident.to_string(), &structs_raw, &mut structs, &mut struct_order, &mut Vec::new())
        {
            errors.push(e);
        }
    }

    let failed_structs: HashSet<String> =
        structs_raw.iter().map(|(s, _)| s.ident.to_string()).filter(|n| !structs.contains_key(n)).collect();
    let mut m = ModuleCtx {
        structs,
        consts: HashMap::new(),
        helpers: HashMap::new(),
        global_names: HashSet::new(),
        spans: RefCell::new(Vec::new()),
        accessors: RefCell::new(Accessors::default()),
        trace_types: RefCell::new(BTreeMap::new()),
        failed: failed_structs,
        report_types: RefCell::new(BTreeMap::new()),
        printf: RefCell::new(BTreeMap::new()),
    };
    for name in m.structs.keys() {
        m.global_names.insert(wgsl_ident(name));
    }

    // Section texts with markers, each with its own integer resolution.
    let mut sections: Vec<(String, String)> = Vec::new(); // (name, finished text)
    let mut source_ranges: Vec<(String, usize, std::ops::Range<usize>)> = Vec::new(); // (item, id, range)

    // Constants.
    for c in &consts_raw {
        let name = c.ident.to_string();
        owners.push((errors.0.len(), owns(&name)));
        let wname = wgsl_ident(&name);
        m.global_names.insert(wname.clone());
        let ty = match m.resolve_type(&c.ty) {
            Ok(t) => t,
            Err(e) => {
                errors.push(e);
                continue;
            }
        };
        let mut l = FnLowerer::new(&m, FnRole::Helper, &wname, Ty::Unit);
        let r = l.expr(&c.expr, Some(&ty));
        match r {
            Ok(v) => {
                if v.ty != ty && !matches!(v.ty, Ty::IntVar(_)) {
                    errors.push(Error::new(
                        c.expr.span(),
                        format!("mismatched types: expected `{ty}`, found `{}`", v.ty),
                    ));
                    continue;
                }
                let text = text::mark(m.span_id(c.span()), &format!("const {wname}: {} = {};\n", ty.wgsl(), v.code));
                let resolve = |_v: u32| match &ty {
                    Ty::Scalar(s) if s.is_int() => *s,
                    _ => crate::types::Scalar::I32,
                };
                let (clean, ranges) = text::finish(&text, &resolve);
                errors.0.extend(l.errors.0);
                for (id, r) in ranges {
                    source_ranges.push((wname.clone(), id, r));
                }
                sections.push((wname.clone(), clean));
                m.consts.insert(name, ConstInfo { wgsl_name: wname, ty });
            }
            Err(e) => errors.push(e),
        }
    }

    for c in &consts_raw {
        if !m.consts.contains_key(&c.ident.to_string()) {
            m.failed.insert(c.ident.to_string());
        }
    }

    // Helper signatures.
    let mut helper_items: HashMap<String, &syn::ItemFn> = HashMap::new();
    for f in &helpers_raw {
        let name = f.sig.ident.to_string();
        owners.push((errors.0.len(), owns(&name)));
        if let Err(e) = check_fn_shape(f) {
            errors.0.extend(e.0);
            continue;
        }
        let mut params = Vec::new();
        let mut ok = true;
        for input in &f.sig.inputs {
            if let syn::FnArg::Typed(pt) = input {
                match m.resolve_type(&pt.ty) {
                    Ok(Ty::Ref(m2, inner)) if inner.is_value() => params.push(Ty::Ref(m2, inner)),
                    Ok(t) if t.is_value() => params.push(t),
                    Ok(t) => {
                        errors.push(Error::new(pt.ty.span(), format!("a parameter cannot have type `{t}`")));
                        ok = false;
                    }
                    Err(e) => {
                        errors.push(e);
                        ok = false;
                    }
                }
            }
        }
        let ret = match &f.sig.output {
            syn::ReturnType::Default => Ty::Unit,
            syn::ReturnType::Type(_, t) => match m.resolve_type(t) {
                Ok(Ty::Ref(..)) => {
                    errors.push(Error::unsupported(t.span(), "returning a reference", "return the value"));
                    ok = false;
                    Ty::Unit
                }
                Ok(t) => t,
                Err(e) => {
                    errors.push(e);
                    ok = false;
                    Ty::Unit
                }
            },
        };
        if !ok {
            continue;
        }
        let wgsl_name = format!("rtf_{name}");
        m.global_names.insert(wgsl_name.clone());
        m.helpers.insert(
            name.clone(),
            HelperSig {
                name: name.clone(),
                wgsl_name,
                params,
                ret,
                intrinsics: Vec::new(),
                traced: Vec::new(),
                resumable: false,
            },
        );
        helper_items.insert(name, f);
    }

    for f in &helpers_raw {
        if !m.helpers.contains_key(&f.sig.ident.to_string()) {
            m.failed.insert(f.sig.ident.to_string());
        }
    }

    // Helper bodies, callees first; helpers that trace also in their
    // resumable form.
    let mut out_resumable_functions: Vec<(String, String)> = Vec::new();
    let mut not_resumable_helpers: Vec<String> = Vec::new();
    let order = match helper_order(&helper_items) {
        Ok(o) => o,
        Err((name, e)) => {
            owners.push((errors.0.len(), owns(&name)));
            errors.push(e);
            Vec::new()
        }
    };
    for name in order {
        owners.push((errors.0.len(), owns(&name)));
        let f = helper_items[&name];
        let sig = m.helpers[&name].clone();
        let params = lparams(f, &sig.params);
        let mut l = FnLowerer::new(&m, FnRole::Helper, &name, sig.ret.clone());
        let body = l.function(&sig.wgsl_name, &params, &f.block);
        let (clean, ranges) = text::finish(&body, &|v| l.resolve_var(v));
        let mut intr: Vec<&'static str> = l.intrinsics.iter().map(|(n, _)| *n).collect();
        intr.sort();
        intr.dedup();
        let traced = l.traced.clone();
        errors.0.extend(l.errors.0);
        for (id, r) in ranges {
            source_ranges.push((sig.wgsl_name.clone(), id, r));
        }
        sections.push((sig.wgsl_name.clone(), clean));
        let h = m.helpers.get_mut(&name).unwrap();
        h.intrinsics = intr;
        h.traced = traced;
        if !h.traced.is_empty() {
            let mut r = FnLowerer::new(&m, FnRole::Helper, &name, sig.ret.clone());
            let rs_name = format!("{}_rs", sig.wgsl_name);
            match r.function_resumable(&rs_name, &params, &f.block) {
                Ok(text) => {
                    let (clean, _) = text::finish(&text, &|v| r.resolve_var(v));
                    out_resumable_functions.push((rs_name, r.fill_frame_saves(&clean)));
                    m.helpers.get_mut(&name).unwrap().resumable = true;
                }
                Err(e) => not_resumable_helpers
                    .push(format!("`{name}`: {}", e.message.strip_prefix("not resumable: ").unwrap_or(&e.message))),
            }
        }
    }

    // The program.
    let mut out = Lowered::default();
    let mut program_text = String::new();
    if let Entry::Program(kind, f) = &entry {
        out.kind = Some(*kind);
        out.name = f.sig.ident.to_string();
        out.wgsl_entry = format!("rtp_{}", f.sig.ident);
        owners.push((errors.0.len(), true));
        match program_unit(&m, *kind, f, &mut out) {
            Ok((text, ranges)) => {
                for (id, r) in ranges {
                    source_ranges.push(("<program>".into(), id, r));
                }
                program_text = text;
            }
            Err(e) => errors.0.extend(e.0),
        }
    } else {
        out.name = match &entry {
            Entry::Helper(f) => f.sig.ident.to_string(),
            Entry::Struct(s) => s.ident.to_string(),
            Entry::Const(c) => c.ident.to_string(),
            Entry::Program(..) => unreachable!(),
        };
        if let Entry::Helper(f) = &entry
            && let Some(h) = m.helpers.get(&f.sig.ident.to_string())
        {
            out.intrinsics = h.intrinsics.iter().map(|s| s.to_string()).collect();
            out.traced = h.traced.clone();
        }
    }
    if !report_deps {
        for (i, e) in errors.0.iter_mut().enumerate() {
            let own = owners.iter().rev().find(|(start, _)| *start <= i).is_none_or(|(_, own)| *own);
            if !own {
                *e = Error::silent(e.span);
            }
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }

    // Assemble the module.
    let spans = m.spans.borrow().clone();
    out.prelude = prelude(&m);
    // WGSL declarations are order-independent: sort for output that does not
    // depend on the order dependencies were collected in.
    struct_order.sort();
    sections.sort();
    for name in &struct_order {
        let d = &m.structs[name];
        let fields: Vec<String> =
            d.fields.iter().map(|(n, t)| format!("    {}: {},", wgsl_ident(n), t.wgsl())).collect();
        out.types.push((d.wgsl_name.clone(), format!("struct {} {{\n{}\n}}\n", d.wgsl_name, fields.join("\n"))));
    }
    for (name, text) in m.accessors.borrow().functions.iter() {
        out.functions.push((name.clone(), text.clone()));
    }
    out.functions.extend(sections);
    out.program = program_text;
    if out.resumable.is_some() {
        out.resumable_functions = out_resumable_functions;
    } else if let Some(why) = &mut out.not_resumable
        && !not_resumable_helpers.is_empty()
    {
        why.push_str(&format!(" ({})", not_resumable_helpers.join("; ")));
    }
    out.printf = m.printf.borrow().iter().map(|(id, (f, t))| (*id, f.clone(), t.clone())).collect();

    let mut wgsl = out.prelude.clone();
    let mut offsets: HashMap<String, usize> = HashMap::new();
    for (name, t) in out.types.iter().chain(out.functions.iter()) {
        wgsl.push('\n');
        offsets.insert(name.clone(), wgsl.len());
        wgsl.push_str(t);
    }
    if !out.program.is_empty() {
        wgsl.push('\n');
        offsets.insert("<program>".into(), wgsl.len());
        wgsl.push_str(&out.program);
    }
    out.wgsl = wgsl;
    let map: Vec<(std::ops::Range<usize>, Span)> = source_ranges
        .iter()
        .filter_map(|(item, id, r)| {
            let base = offsets.get(item)?;
            Some((base + r.start..base + r.end, *spans.get(*id)?))
        })
        .collect();
    let fallback = match &entry {
        Entry::Program(_, f) | Entry::Helper(f) => f.sig.ident.span(),
        Entry::Struct(s) => s.ident.span(),
        Entry::Const(c) => c.ident.span(),
    };
    crate::validate::validate(&out.wgsl, &map, fallback)?;
    if let Some(r) = &out.resumable {
        // The resumable form is generated from a program that validated:
        // an error here is the compiler's, and the program falls back to
        // the plain form.
        let mut wgsl = out.wgsl[..offsets["<program>"]].to_string();
        wgsl.push_str(&resumable_stubs(&m));
        for (_, t) in &out.resumable_functions {
            wgsl.push_str(t);
        }
        wgsl.push_str(r);
        if let Err(e) = crate::validate::validate(&wgsl, &[], fallback) {
            out.not_resumable = Some(format!("internal error, naga: {}", e.messages().join("; ")));
            out.resumable = None;
            out.resumable_functions.clear();
        }
    }
    Ok(out)
}

/// The dependencies `entry` reaches, directly or through other dependencies
/// (callers may pass a superset, such as every item of a file).
fn reachable(entry: &Entry<'_>, deps: &[Item]) -> Vec<Item> {
    let names_of = |paths: Vec<syn::Path>| -> Vec<String> {
        paths.iter().filter_map(|p| p.segments.last().map(|s| s.ident.to_string())).collect()
    };
    let mut todo = match entry {
        Entry::Program(_, f) | Entry::Helper(f) => names_of(crate::deps::of_fn(f)),
        Entry::Struct(s) => names_of(crate::deps::of_struct(s)),
        Entry::Const(c) => names_of(crate::deps::of_const(c)),
    };
    let mut seen: HashSet<String> = HashSet::new();
    let mut out = Vec::new();
    while let Some(n) = todo.pop() {
        if !seen.insert(n.clone()) {
            continue;
        }
        if let Some(item) = deps.iter().find(|d| d.name() == n) {
            todo.extend(names_of(match item {
                Item::Struct(s, _) => crate::deps::of_struct(s),
                Item::Function(f) => crate::deps::of_fn(f),
                Item::Const(c) => crate::deps::of_const(c),
            }));
            out.push(item.clone());
        }
    }
    // Keep the caller's order for stable output.
    out.sort_by_key(|i| deps.iter().position(|d| d.name() == i.name()));
    out
}

/// Rejects function shapes the subset has no use for.
fn check_fn_shape(f: &syn::ItemFn) -> std::result::Result<(), Errors> {
    let mut errors = Errors::default();
    if !f.sig.generics.params.is_empty() {
        errors.push(Error::unsupported(f.sig.generics.span(), "a generic function", "write one function per type"));
    }
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
    }
    if errors.is_empty() { Ok(()) } else { Err(errors) }
}

fn lparams(f: &syn::ItemFn, tys: &[Ty]) -> Vec<LParam> {
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

/// Orders helpers callees-first; a cycle is recursion, which WGSL lacks (the
/// error comes with the helper whose call closes the cycle).
fn helper_order(items: &HashMap<String, &syn::ItemFn>) -> std::result::Result<Vec<String>, (String, Error)> {
    let mut calls: HashMap<String, Vec<(String, Span)>> = HashMap::new();
    for (name, f) in items {
        let mut found = Vec::new();
        collect_calls(&f.block, &mut found);
        calls.insert(name.clone(), found.into_iter().filter(|(c, _)| items.contains_key(c)).collect());
    }
    let mut order = Vec::new();
    let mut state: HashMap<String, u8> = HashMap::new();
    fn visit(
        n: &str,
        calls: &HashMap<String, Vec<(String, Span)>>,
        state: &mut HashMap<String, u8>,
        order: &mut Vec<String>,
    ) -> std::result::Result<(), (String, Error)> {
        state.insert(n.to_string(), 1);
        for (c, span) in &calls[n] {
            match state.get(c) {
                Some(1) => {
                    let what = if n == c {
                        format!("recursion (`{n}` calls itself)")
                    } else {
                        format!("recursion (`{n}` calls `{c}`, which leads back to `{n}`)")
                    };
                    return Err((
                        n.to_string(),
                        Error::unsupported(*span, &what, "WGSL has no recursion; rewrite it as a loop"),
                    ));
                }
                Some(2) => {}
                _ => visit(c, calls, state, order)?,
            }
        }
        state.insert(n.to_string(), 2);
        order.push(n.to_string());
        Ok(())
    }
    let mut names: Vec<&String> = items.keys().collect();
    names.sort();
    for n in names {
        if !state.contains_key(n) {
            visit(n, &calls, &mut state, &mut order)?;
        }
    }
    Ok(order)
}

/// Names of functions called in a block, with the call span.
pub fn collect_calls(block: &syn::Block, out: &mut Vec<(String, Span)>) {
    struct V<'a>(&'a mut Vec<(String, Span)>);
    impl<'ast> syn::visit::Visit<'ast> for V<'_> {
        fn visit_expr_call(&mut self, c: &'ast syn::ExprCall) {
            if let syn::Expr::Path(p) = &*c.func
                && let Some(seg) = p.path.segments.last()
            {
                self.0.push((seg.ident.to_string(), c.span()));
            }
            syn::visit::visit_expr_call(self, c);
        }
    }
    syn::visit::Visit::visit_block(&mut V(out), block);
}

type ProgramText = (String, Vec<(usize, std::ops::Range<usize>)>);

fn program_unit(
    m: &ModuleCtx,
    kind: Kind,
    f: &syn::ItemFn,
    out: &mut Lowered,
) -> std::result::Result<ProgramText, Errors> {
    check_fn_shape(f)?;
    let params = signature::program_params(kind, f)?;
    let mut errors = Errors::default();
    let mut lps = Vec::new();
    for p in &params {
        let ty = match m.resolve_type(&p.ty) {
            Ok(t) => t,
            Err(e) => {
                errors.push(e);
                continue;
            }
        };
        let lty = match p.role {
            Role::Payload { mutable } => {
                match &ty {
                    Ty::Struct(s) if s.role == StructRole::Payload => {}
                    other => errors.push(Error::new(
                        p.ty.span(),
                        format!("the payload of {} must be a #[rt_payload] struct, found `{other}`", kind.a_program()),
                    )),
                }
                out.payload = Some(ty.clone());
                if mutable { Ty::Ref(true, Box::new(ty)) } else { ty }
            }
            Role::Attributes { mutable } => {
                match &ty {
                    Ty::Struct(s) if s.role == StructRole::Attributes => {}
                    other => errors.push(Error::new(
                        p.ty.span(),
                        format!(
                            "the attributes of {} must be a #[rt_attributes] struct, found `{other}`",
                            kind.a_program()
                        ),
                    )),
                }
                out.attributes = Some(ty.clone());
                if mutable { Ty::Ref(true, Box::new(ty)) } else { Ty::Ref(false, Box::new(ty)) }
            }
            Role::Primitive => ty,
            Role::Variable => {
                let ok = ty.is_plain_data() || matches!(ty, Ty::Buffer(..) | Ty::Sampler | Ty::Object);
                if !ok {
                    errors.push(Error::new(p.ty.span(), format!("a variable cannot have type `{ty}`")));
                }
                // The linker loads variable records from the heap: make sure
                // the loader of every plain-data variable type is in the module.
                if ty.is_plain_data() {
                    m.accessors.borrow_mut().load(&ty);
                }
                out.variables.push((p.name.to_string(), ty.clone()));
                ty
            }
        };
        let mutable_binding = f.sig.inputs.iter().any(|i| match i {
            syn::FnArg::Typed(pt) => {
                matches!(&*pt.pat, syn::Pat::Ident(pi) if pi.ident == p.name && pi.mutability.is_some())
            }
            _ => false,
        });
        lps.push(LParam { rust: p.name.to_string(), ty: lty, mutable_binding, span: p.span });
    }
    let ret = match (&f.sig.output, kind) {
        (syn::ReturnType::Default, Kind::BoundingBox) => {
            errors.push(Error::new(
                f.sig.ident.span(),
                "a bounding_box program must return the primitive's bounds: add `-> Aabb` to its signature",
            ));
            Ty::Unit
        }
        (syn::ReturnType::Default, Kind::Visit) => {
            errors.push(Error::new(
                f.sig.ident.span(),
                "a visit program must return the child to enter: add `-> u32` to its signature",
            ));
            Ty::Unit
        }
        (syn::ReturnType::Default, _) => Ty::Unit,
        (syn::ReturnType::Type(_, t), k) => {
            let want = match k {
                Kind::BoundingBox => Ty::Aabb,
                Kind::Visit => crate::types::U32,
                _ => Ty::Unit,
            };
            match m.resolve_type(t) {
                Ok(got) if got == want => got,
                Ok(got) => {
                    let msg = if want == Ty::Unit {
                        format!("{} returns nothing; write results into the payload or a buffer", k.a_program())
                    } else {
                        format!("{} returns `{want}`, not `{got}`", k.a_program())
                    };
                    errors.push(Error::new(t.span(), msg));
                    want
                }
                Err(e) => {
                    errors.push(e);
                    want
                }
            }
        }
    };
    if !errors.is_empty() {
        return Err(errors);
    }
    // The WGSL function takes its parameters in one canonical order whatever
    // the Rust order: payload, attributes, primitive index, then variables
    // (in declaration order), so the linker can call every program alike.
    let rank = |p: &signature::Param| match p.role {
        Role::Payload { .. } => 0,
        Role::Attributes { .. } => 1,
        Role::Primitive => 2,
        Role::Variable => 3,
    };
    let mut order: Vec<usize> = (0..lps.len()).collect();
    order.sort_by_key(|i| rank(&params[*i]));
    let mut slots: Vec<Option<LParam>> = lps.into_iter().map(Some).collect();
    let lps: Vec<LParam> = order.into_iter().filter_map(|i| slots[i].take()).collect();
    let name = f.sig.ident.to_string();
    let mut l = FnLowerer::new(m, FnRole::Program(kind), &name, ret);
    let text = l.function(&out.wgsl_entry, &lps, &f.block);
    let (clean, ranges) = text::finish(&text, &|v| l.resolve_var(v));
    let mut intr: Vec<String> = l.intrinsics.iter().map(|(n, _)| n.to_string()).collect();
    intr.sort();
    intr.dedup();
    out.intrinsics = intr;
    out.traced = l.traced.clone();
    out.traced.dedup();
    if !l.errors.is_empty() {
        return Err(l.errors);
    }
    if !out.traced.is_empty() {
        let mut r = FnLowerer::new(m, FnRole::Program(kind), &name, Ty::Unit);
        match r.function_resumable(&out.wgsl_entry, &lps, &f.block) {
            Ok(text) => {
                let (clean, _) = text::finish(&text, &|v| r.resolve_var(v));
                out.resumable = Some(r.fill_frame_saves(&clean));
            }
            Err(e) => out.not_resumable = Some(e.message),
        }
    }
    Ok((clean, ranges))
}

/// Stubs for everything the runtime provides. They only need the right
/// signatures: the linker replaces this whole section.
fn prelude(m: &ModuleCtx) -> String {
    let mut s = PRELUDE.clone();
    for ty in m.trace_types.borrow().values() {
        s.push_str(&format!(
            "fn rt_trace_{}(object: u32, ray: RtRay, prd: ptr<function, {}>, flags: u32, mask: u32) {{}}\n",
            ty.mangle(),
            ty.wgsl()
        ));
    }
    for ty in m.report_types.borrow().values() {
        s.push_str(&format!(
            "fn rt_report_intersection_{}(material: u32, attr: ptr<function, {}>) -> bool {{ return false; }}\n",
            ty.mangle(),
            ty.wgsl()
        ));
    }
    s
}

/// Stubs for what the linker provides to resumable programs.
pub fn resumable_stubs(m: &ModuleCtx) -> String {
    let mut s = String::from("var<private> rt_rs: u32;\nvar<private> rt_d: u32;\nconst RT_DEPTHS: u32 = 1u;\n");
    for ty in m.trace_types.borrow().values() {
        let (p, w) = (ty.mangle(), ty.wgsl());
        s.push_str(&format!(
            "fn rt_request_{p}(object: u32, ray: RtRay, prd: {w}, flags: u32, mask: u32) {{}}\nfn rt_result_{p}() -> {w} {{\n    var p: {w};\n    return p;\n}}\n"
        ));
    }
    s
}

/// The fixed part of the stub prelude: the contract's records and a stub
/// of every runtime function (`rt_abi::wgsl::stub_prelude`).
pub static PRELUDE: std::sync::LazyLock<String> = std::sync::LazyLock::new(rt_abi::wgsl::stub_prelude);
