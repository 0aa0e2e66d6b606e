//! Lowering: a unit (one program, helper, struct or constant, plus every
//! item it depends on) to one standalone WGSL module with a source map.
//!
//! The module is laid out as four sections the runtime's linker relies on:
//! a *prelude* of runtime stubs (replaced at link time by the real runtime),
//! the *types*, the *functions* (accessors, constants and helpers) and the
//! *program*. Names: programs are `rtp_<name>`, helpers `rtf_<name>` (an
//! instance of a generic one `rtf_<name>__<arguments>`, see [`generics`]), the
//! methods and associated functions of an `#[rt_impl]` `rtm_<Type>__<name>`
//! and its constants `<Type>__<NAME>`, runtime items `rt_*`/`Rt*`; user
//! structs and constants keep their names, an instance of a generic struct
//! is `rt_<Type>__<arguments>` (see [`generic_structs`]).
//!
//! [`lower`] runs the phases of `unit` in order, in passes while calls
//! ask for instances of generic helpers the pass lacked: the items the entry
//! reaches (`items`), sorted by dependency (`order`); constants; helper
//! signatures, then bodies, callees first ([`func`] lowers one body); the
//! program (`program`); and `assemble`s and validates the module.

pub mod accessors;
mod assemble;
pub mod builtins;
pub mod func;
pub mod generic_structs;
pub mod generics;
mod items;
mod order;
mod program;
pub mod resolve;
pub mod text;
mod unit;
pub mod value;

use crate::Item;
use crate::error::{Error, Errors, Result};
use crate::kinds::Kind;
use crate::types::{EnumDef, StructDef, Ty};
use accessors::Accessors;
use func::LParam;
use proc_macro2::Span;
use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::rc::Rc;

pub use assemble::{ATOMIC_PRELUDE, PRELUDE, resumable_stubs};
pub use items::collect_calls;
pub use resolve::{is_reserved, resolve_type, wgsl_ident};

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
    /// A method of an `#[rt_impl]` (see `methods`): its first parameter is
    /// the receiver, and `value.name(..)` calls it.
    pub has_receiver: bool,
}

#[derive(Clone, Debug)]
pub struct ConstInfo {
    pub wgsl_name: String,
    pub ty: Ty,
}

/// Module-wide state shared by the functions being lowered.
pub struct ModuleCtx {
    pub structs: HashMap<String, Rc<StructDef>>,
    pub enums: HashMap<String, Rc<EnumDef>>,
    /// The tuple types the module uses, by WGSL name: each is declared as a
    /// struct.
    pub tuples: RefCell<BTreeMap<String, Ty>>,
    pub consts: HashMap<String, ConstInfo>,
    pub helpers: HashMap<String, HelperSig>,
    pub global_names: HashSet<String>,
    spans: RefCell<Vec<Span>>,
    pub accessors: RefCell<Accessors>,
    pub trace_types: RefCell<BTreeMap<String, Ty>>,
    pub report_types: RefCell<BTreeMap<String, Ty>>,
    /// The signatures called through `Callable` ids, by dispatch name: each
    /// has a stub in the prelude, the linker's `switch` in a megakernel.
    pub call_types: RefCell<BTreeMap<String, Rc<crate::types::CallSig>>>,
    /// Dependencies that failed to lower: using them is a silent error.
    pub failed: HashSet<String>,
    /// The generic helpers, by name: called through their instances.
    pub generics: HashMap<String, Rc<syn::ItemFn>>,
    /// The instances calls asked for (see `generics`), in order.
    pub wanted: RefCell<Vec<generics::Instance>>,
    /// The generic structs and their instances built so far.
    pub generic_structs: generic_structs::GenericStructs,
    /// Whether `debug_assert!`s are lowered to their checks, or dropped
    /// (see [`lower_own_without_debug_assertions`]).
    pub debug_assertions: bool,
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

    /// The tuple of `elems`, declared in the module.
    pub fn tuple(&self, elems: Vec<Ty>) -> Ty {
        let t = Ty::Tuple(elems);
        self.note_tuples(&t);
        t
    }

    /// Declares every tuple type `ty` contains.
    pub fn note_tuples(&self, ty: &Ty) {
        match ty {
            Ty::Tuple(ts) => {
                for t in ts {
                    self.note_tuples(t);
                }
                self.tuples.borrow_mut().entry(ty.wgsl()).or_insert_with(|| ty.clone());
            }
            // An `Option` is a struct of its own, declared as a tuple is.
            Ty::Option(t) => {
                self.note_tuples(t);
                self.tuples.borrow_mut().entry(ty.wgsl()).or_insert_with(|| ty.clone());
            }
            Ty::Array(t, _) | Ty::Ref(_, t) | Ty::Buffer(_, t) | Ty::BufferId(_, t) => self.note_tuples(t),
            _ => {}
        }
    }

    /// The user type `name` names with `args` (see `resolve::UserTypes`):
    /// a struct, an enum, or an instance of a generic struct, built on
    /// first use.
    pub fn user_type(&self, name: &str, args: Option<&[Ty]>, span: Span) -> Option<Result<Ty>> {
        if let Some(t) = self.generic_structs.instance(name, args, span, &|n, a, s| self.user_type(n, a, s)) {
            if let Ok(Ty::Struct(d)) = &t {
                for (_, f) in &d.fields {
                    self.note_tuples(f);
                }
            }
            return Some(t);
        }
        if let Some(args) = args {
            return (self.structs.contains_key(name) || self.enums.contains_key(name)).then(|| {
                Err(Error::new(
                    span,
                    format!("`{name}` takes no generic arguments (found {}): it is not a generic struct", args.len()),
                ))
            });
        }
        self.structs
            .get(name)
            .map(|d| Ok(Ty::Struct(d.clone())))
            .or_else(|| self.enums.get(name).map(|e| Ok(Ty::Enum(e.clone()))))
    }

    pub fn resolve_type(&self, ty: &syn::Type) -> Result<Ty> {
        let resolved = resolve_type(ty, &|n, a, s| self.user_type(n, a, s));
        if let Ok(t) = &resolved {
            self.note_tuples(t);
        }
        resolved.map_err(|e| {
            // A struct whose own declaration failed: that error is enough.
            let failed = |i: &proc_macro2::Ident| self.failed.contains(&i.to_string());
            if generics::names_any(quote::quote!(#ty), &failed) { Error::silent(e.span) } else { e }
        })
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
    /// A callable program's argument types, in order.
    pub arguments: Vec<Ty>,
    /// A callable program's signature.
    pub callable: Option<crate::types::CallSig>,
    /// The signatures of the callables the module calls, by dispatch name.
    pub calls: BTreeMap<String, std::rc::Rc<crate::types::CallSig>>,
    /// A tracing program's resumable form (frame declarations and the
    /// function; see `func/resume.rs`), validated like the plain form.
    pub resumable: Option<String>,
    /// Why a tracing program has no resumable form.
    pub not_resumable: Option<String>,
    /// Resumable forms of the helpers that trace (`(name, text)`, callees
    /// first).
    pub resumable_functions: Vec<(String, String)>,
    /// Per plain function, by WGSL name (the program under `wgsl_entry`,
    /// each helper under its own): the names per-depth clones rename and
    /// the byte offsets where they end, in text order (`text::Site`).
    pub sites: BTreeMap<String, Vec<(text::Site, usize)>>,
    /// The program's body with each expression's type (`crate::typed`).
    pub typed: Option<crate::typed::Typed>,
    /// The same for each helper the module lowered, by Rust name.
    pub typed_helpers: Vec<(String, crate::typed::Typed)>,
}

/// The entry being lowered.
pub enum Entry<'a> {
    Program(Kind, &'a syn::ItemFn),
    Helper(&'a syn::ItemFn),
    Struct(&'a syn::ItemStruct),
    Const(&'a syn::ItemConst),
    /// An `#[rt_enum]` with `#[rt_impl]` blocks: its chain checks them.
    Enum(&'a syn::ItemEnum),
}

/// Lowers `entry` with its dependencies `deps` into a validated module.
/// Errors in the dependencies are reported too (see [`lower_own`]).
pub fn lower(entry: Entry<'_>, deps: &[Item]) -> std::result::Result<Lowered, Errors> {
    lower_impl(entry, deps, true, true)
}

/// Like [`lower`], with every `debug_assert!` dropped: the module of a
/// build without debug assertions.
pub fn lower_without_debug_assertions(entry: Entry<'_>, deps: &[Item]) -> std::result::Result<Lowered, Errors> {
    lower_impl(entry, deps, true, false)
}

/// Like [`lower`], but errors inside dependencies are silent: in the macro
/// chain each dependency's own macro reports them, so a helper's mistake is
/// shown once, not again at every program that calls it.
pub fn lower_own(entry: Entry<'_>, deps: &[Item]) -> std::result::Result<Lowered, Errors> {
    lower_impl(entry, deps, false, true)
}

/// Like [`lower_own`], with every `debug_assert!` dropped. A program
/// whose code has one is lowered both ways, and its descriptor chooses by
/// the `cfg(debug_assertions)` of the crate that declares it (see
/// `expand/chain.rs`): the two modules differ in more than the checks (a
/// site's offset), so neither is derived from the other.
pub fn lower_own_without_debug_assertions(entry: Entry<'_>, deps: &[Item]) -> std::result::Result<Lowered, Errors> {
    lower_impl(entry, deps, false, false)
}

fn lower_impl(
    entry: Entry<'_>,
    deps: &[Item],
    report_deps: bool,
    debug_assertions: bool,
) -> std::result::Result<Lowered, Errors> {
    // Type aliases are replaced by what they stand for (`aliases`), on
    // copies of the unit's items where it has any.
    let entry_body = match &entry {
        Entry::Program(_, f) | Entry::Helper(f) => Some(&*f.block),
        _ => None,
    };
    let mut kind = None;
    let resolved = if crate::aliases::needed(entry_body, deps) {
        let item = match &entry {
            Entry::Program(k, f) => {
                kind = Some(*k);
                Item::Function((*f).clone())
            }
            Entry::Helper(f) => Item::Function((*f).clone()),
            Entry::Struct(s) => Item::Struct((*s).clone(), crate::StructRole::Data),
            Entry::Const(c) => Item::Const((*c).clone()),
            Entry::Enum(e) => Item::Enum((*e).clone()),
        };
        Some(crate::aliases::resolve(item, deps)?)
    } else {
        None
    };
    let (entry, deps) = match &resolved {
        Some((item, deps)) => (entry_of(kind, item), &deps[..]),
        None => (entry, deps),
    };
    // The lowering reads functions with their sugar rewritten, and the
    // functions declared in their bodies as helpers beside them (`sugar`).
    let mut taken: HashSet<String> = deps.iter().map(Item::name).collect();
    let mut nested = Vec::new();
    let closures = crate::sugar::ClosureHelpers::new(
        deps.iter().filter_map(|d| match d {
            Item::Function(f) => Some(f),
            _ => None,
        }),
        deps.iter().filter_map(|d| match d {
            Item::Impl(i) => Some(i),
            _ => None,
        }),
    );
    let mut cx = crate::sugar::Cx { closures, inlined: 0, errors: Errors::default() };
    let sweetened;
    let entry = match entry {
        Entry::Program(kind, f) => {
            taken.insert(f.sig.ident.to_string());
            sweetened = crate::sugar::function(f, &mut taken, &mut nested, &mut cx);
            Entry::Program(kind, &sweetened)
        }
        Entry::Helper(f) => {
            taken.insert(f.sig.ident.to_string());
            sweetened = crate::sugar::function(f, &mut taken, &mut nested, &mut cx);
            Entry::Helper(&sweetened)
        }
        other => other,
    };
    let mut deps: Vec<Item> = deps.iter().map(|d| crate::sugar::item(d, &mut taken, &mut nested, &mut cx)).collect();
    if !cx.errors.is_empty() {
        return Err(cx.errors);
    }
    deps.extend(nested.into_iter().map(Item::Function));
    if let Entry::Helper(f) = &entry
        && (generics::is_generic(f) || crate::sugar::takes_closure(&f.sig))
    {
        // Its body is checked per instance, by the callers (`generics`);
        // one given a closure, where it is inlined (`sugar`).
        let mut errors = items::check_fn_shape(f).err().unwrap_or_default();
        errors.0.extend(generics::check_alone(f).err().unwrap_or_default().0);
        if !errors.is_empty() {
            return Err(errors);
        }
        return Ok(Lowered { name: f.sig.ident.to_string(), ..Lowered::default() });
    }
    let deps = items::reachable(&entry, &deps);
    // Passes until every instance of a generic helper the unit calls is
    // among its helpers (see `generics`).
    let mut instances: Vec<generics::Instance> = Vec::new();
    loop {
        let more = match lower_pass(&entry, &deps, &instances, report_deps, debug_assertions) {
            Pass::Done(r) => return *r,
            Pass::More(more) => more,
        };
        let too_long = more.iter().any(|i| i.key().len() > generics::MAX_KEY);
        if too_long || instances.len() + more.len() > generics::MAX_INSTANCES {
            let (name, span) = match &entry {
                Entry::Program(_, f) | Entry::Helper(f) => (f.sig.ident.to_string(), f.sig.ident.span()),
                Entry::Struct(s) => (s.ident.to_string(), s.ident.span()),
                Entry::Const(c) => (c.ident.to_string(), c.ident.span()),
                Entry::Enum(e) => (e.ident.to_string(), e.ident.span()),
            };
            let mut last = more.last().map(generics::Instance::key).unwrap_or_default();
            if last.len() > 60 {
                last = format!("{}...", last.chars().take(60).collect::<String>());
            }
            return Err(Error::new(
                span,
                format!(
                    "`{name}` calls generic helpers at ever new types (`{last}`, after {} instances): a generic \
                     that calls itself, through others, at a new type each time never ends; give it fixed types",
                    instances.len()
                ),
            )
            .into());
        }
        instances.extend(more);
    }
}

/// The entry `item` is, a program where `kind` says so (the inverse of
/// the entry's item in [`lower_impl`]).
fn entry_of(kind: Option<Kind>, item: &Item) -> Entry<'_> {
    match (item, kind) {
        (Item::Function(f), Some(k)) => Entry::Program(k, f),
        (Item::Function(f), None) => Entry::Helper(f),
        (Item::Struct(s, _), _) => Entry::Struct(s),
        (Item::Const(c), _) => Entry::Const(c),
        (Item::Enum(e), _) => Entry::Enum(e),
        _ => unreachable!("an entry is a function, struct, constant or enum"),
    }
}

/// What one pass over a unit ends with: the module, or instances of
/// generic helpers the pass did not have.
enum Pass {
    Done(Box<std::result::Result<Lowered, Errors>>),
    More(Vec<generics::Instance>),
}

fn lower_pass(
    entry: &Entry<'_>,
    deps: &[Item],
    instances: &[generics::Instance],
    report_deps: bool,
    debug_assertions: bool,
) -> Pass {
    let mut unit = unit::Unit::new(entry);
    let items::ByKind {
        structs: structs_raw,
        fns: helpers_raw,
        consts: consts_raw,
        failed: failed_members,
        generics: generic_fns,
        generic_structs,
    } = items::by_kind(entry, deps, instances);
    let consts_raw = items::const_order(&consts_raw);
    let (enums, failed_enums) = items::enums(deps);
    let generic_structs = generic_structs::GenericStructs::new(generic_structs);
    let (structs, struct_order) = unit.build_structs(&structs_raw, &enums, &generic_structs);
    let mut failed_structs: HashSet<String> =
        structs_raw.iter().map(|(s, _)| s.ident.to_string()).filter(|n| !structs.contains_key(n)).collect();
    failed_structs.extend(failed_enums);
    failed_structs.extend(failed_members);
    let mut m = ModuleCtx {
        structs,
        enums,
        tuples: RefCell::new(BTreeMap::new()),
        consts: HashMap::new(),
        helpers: HashMap::new(),
        global_names: HashSet::new(),
        spans: RefCell::new(Vec::new()),
        accessors: RefCell::new(Accessors::default()),
        trace_types: RefCell::new(BTreeMap::new()),
        failed: failed_structs,
        report_types: RefCell::new(BTreeMap::new()),
        call_types: RefCell::new(BTreeMap::new()),
        printf: RefCell::new(BTreeMap::new()),
        generics: generic_fns,
        wanted: RefCell::new(Vec::new()),
        generic_structs,
        debug_assertions,
    };
    for (name, d) in &m.structs {
        m.global_names.insert(wgsl_ident(name));
        for (_, t) in &d.fields {
            m.note_tuples(t);
        }
    }
    unit.lower_consts(&mut m, &consts_raw);
    let helper_items = unit.helper_signatures(&mut m, &helpers_raw);
    unit.lower_helpers(&mut m, &helper_items);
    let mut out = Lowered::default();
    let program_text = unit.lower_entry(&m, &mut out);
    let more: Vec<generics::Instance> = m.wanted.take().into_iter().filter(|w| !instances.contains(w)).collect();
    if !more.is_empty() {
        return Pass::More(more);
    }
    if !report_deps {
        unit.silence_dependencies();
    }
    if !unit.errors.is_empty() {
        return Pass::Done(Box::new(Err(unit.errors)));
    }
    Pass::Done(Box::new(assemble::assemble(&m, entry, unit, struct_order, program_text, out)))
}
