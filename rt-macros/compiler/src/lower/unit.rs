//! Lowering one unit, phase by phase: constants, helper signatures, helper
//! bodies (callees first, with their resumable forms), then the entry; each
//! error is kept with the item it came from, so that errors of
//! dependencies can be silenced (see `lower_own`).

use super::func::{FnLowerer, FnRole};
use super::items::{ConstDef, FnDef, StructGraph, StructNode, check_fn_shape, helper_order, lparams};
use super::order::Order;
use super::program::program_unit;
use super::{ConstInfo, Entry, HelperSig, Lowered, ModuleCtx, text};
use crate::StructRole;
use crate::error::{Error, Errors};
use crate::types::{EnumDef, Scalar, StructDef, Ty};
use proc_macro2::Span;
use std::collections::HashMap;
use std::ops::Range;
use std::rc::Rc;
use syn::spanned::Spanned;

/// A unit being lowered: its errors and their owners, and the text of
/// each section lowered so far.
pub(super) struct Unit<'e, 'a> {
    entry: &'e Entry<'a>,
    pub errors: Errors,
    /// Which item each error came from: `(index of its first error, is the
    /// entry)`, in order.
    owners: Vec<(usize, bool)>,
    /// Section texts, markers resolved: `(name, text)`.
    pub sections: Vec<(String, String)>,
    /// Source-map entries: `(section, span id, byte range in the section)`.
    pub source_ranges: Vec<(String, usize, Range<usize>)>,
    /// The helpers' sites (see [`Lowered::sites`]): `(name, sites)`.
    pub sites: Vec<(String, Vec<(text::Site, usize)>)>,
    /// Resumable forms of the helpers that trace: `(name, text)`.
    pub resumable_functions: Vec<(String, String)>,
    /// The typed form of each helper lowered, by Rust name.
    pub typed_helpers: Vec<(String, crate::typed::Typed)>,
    /// Why tracing helpers have no resumable form.
    pub not_resumable_helpers: Vec<String>,
}

impl<'e, 'a> Unit<'e, 'a> {
    pub fn new(entry: &'e Entry<'a>) -> Self {
        Unit {
            entry,
            errors: Errors::default(),
            owners: Vec::new(),
            sections: Vec::new(),
            source_ranges: Vec::new(),
            sites: Vec::new(),
            resumable_functions: Vec::new(),
            typed_helpers: Vec::new(),
            not_resumable_helpers: Vec::new(),
        }
    }

    /// Whether an item is the entry itself (a struct's impl is the
    /// struct's: its chain reports the impl's errors; see `methods`).
    fn owns(&self, name: &str) -> bool {
        match self.entry {
            // An instance of a generic helper is its caller's: the
            // generic's own macro has no types to check it with.
            _ if name.contains('<') => true,
            Entry::Helper(f) => f.sig.ident == name,
            Entry::Struct(s) => s.ident == name || name.starts_with(&format!("{}::", s.ident)),
            Entry::Const(c) => c.ident == name,
            Entry::Enum(e) => e.ident == name || name.starts_with(&format!("{}::", e.ident)),
            Entry::Program(..) => false,
        }
    }

    /// Errors from here on are the item `name`'s.
    pub fn own(&mut self, name: &str) {
        self.owners.push((self.errors.0.len(), self.owns(name)));
    }

    /// Makes the errors of items other than the entry silent.
    pub fn silence_dependencies(&mut self) {
        for (i, e) in self.errors.0.iter_mut().enumerate() {
            let own = self.owners.iter().rev().find(|(start, _)| *start <= i).is_none_or(|(_, own)| *own);
            if !own {
                *e = Error::silent(e.span);
            }
        }
    }

    /// Builds the structs in dependency order: their definitions, and
    /// their names in the order built.
    pub fn build_structs(
        &mut self,
        raw: &[(&syn::ItemStruct, StructRole)],
        enums: &HashMap<String, Rc<EnumDef>>,
        generic: &super::generic_structs::GenericStructs,
    ) -> (HashMap<String, Rc<StructDef>>, Vec<String>) {
        let mut graph = StructGraph::new(raw, enums, generic);
        let mut order = Order::new();
        for (s, _) in raw {
            self.own(&s.ident.to_string());
            if let Err(e) = order.visit(&mut graph, &StructNode::Struct(s.ident.to_string())) {
                self.errors.push(e);
            }
        }
        let names = order
            .nodes
            .into_iter()
            .filter_map(|n| match n {
                StructNode::Struct(name) => Some(name),
                StructNode::Field(..) => None,
            })
            .collect();
        (graph.defs, names)
    }

    /// Lowers the constants, in dependency order.
    pub fn lower_consts(&mut self, m: &mut ModuleCtx, consts: &[ConstDef]) {
        for def in consts {
            let c = &def.c;
            let name = def.key.clone();
            let first_error = self.errors.0.len();
            let plain = crate::plain_consts::is_plain(c);
            if plain {
                // No macro of its own reports its errors.
                self.owners.push((first_error, true));
            } else {
                self.own(&name);
            }
            self.lower_const(m, def);
            if plain {
                for e in &mut self.errors.0[first_error..] {
                    e.message = format!("in the constant `{name}` (a plain `const` of this module): {}", e.message);
                }
            }
        }
        for c in consts {
            if !m.consts.contains_key(&c.key) {
                m.failed.insert(c.key.clone());
            }
        }
    }

    /// Lowers one constant into `m` (see [`Unit::lower_consts`]).
    fn lower_const(&mut self, m: &mut ModuleCtx, def: &ConstDef) {
        let c = &def.c;
        let name = def.key.clone();
        let wname = def.wgsl_name.clone();
        m.global_names.insert(wname.clone());
        let ty = match m.resolve_type(&c.ty) {
            Ok(t) => t,
            Err(e) => {
                self.errors.push(e);
                return;
            }
        };
        let mut l = FnLowerer::new(m, FnRole::Helper, &wname, Ty::Unit);
        let r = l.expr(&c.expr, Some(&ty));
        match r {
            Ok(v) => {
                if v.ty != ty && !matches!(v.ty, Ty::IntVar(_)) {
                    self.errors.push(Error::new(
                        c.expr.span(),
                        format!("mismatched types: expected `{ty}`, found `{}`", v.ty),
                    ));
                    return;
                }
                if v.code.contains(rt_abi::wgsl::F32_FROM_BITS) {
                    self.errors.push(Error::new(
                        c.expr.span(),
                        format!(
                            "constant `{name}` is infinite or NaN, which a WGSL constant cannot hold; \
                             write `f32::INFINITY` (or `f32::NAN`) where it is used, or declare it \
                             as a `const` inside the function"
                        ),
                    ));
                    return;
                }
                let text = text::mark(m.span_id(c.span()), &format!("const {wname}: {} = {};\n", ty.wgsl(), v.code));
                // A constant's integer literals take its type.
                let signed = |_v: u32| !matches!(ty, Ty::Scalar(Scalar::U32 | Scalar::Usize));
                let done = text::finish(&text, &signed);
                self.errors.0.extend(l.errors.0);
                for (id, r) in done.ranges {
                    self.source_ranges.push((wname.clone(), id, r));
                }
                self.sections.push((wname.clone(), done.text));
                m.consts.insert(name, ConstInfo { wgsl_name: wname, ty });
            }
            Err(e) => self.errors.push(e),
        }
    }

    /// Checks the helpers' signatures; returns the helpers that have one.
    pub fn helper_signatures(&mut self, m: &mut ModuleCtx, helpers_raw: &[FnDef]) -> HashMap<String, FnDef> {
        let mut helper_items: HashMap<String, FnDef> = HashMap::new();
        for def in helpers_raw {
            let f = &def.f;
            let name = def.key.clone();
            self.own(&name);
            if let Err(e) = check_fn_shape(f) {
                self.errors.0.extend(e.0);
                continue;
            }
            let first = self.errors.0.len();
            let sig = helper_signature(m, f, &mut self.errors);
            note_instance(&mut self.errors, first, def);
            let Some((params, ret)) = sig else { continue };
            let wgsl_name = def.wgsl_name.clone();
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
                    has_receiver: def.has_receiver,
                },
            );
            helper_items.insert(name, def.clone());
        }

        for f in helpers_raw {
            if !m.helpers.contains_key(&f.key) {
                m.failed.insert(f.key.clone());
            }
        }
        helper_items
    }

    /// The method calls each function makes, by caller: only the
    /// receiver's type says which method `value.name(..)` calls, so the
    /// bodies are lowered once for their types (the result is dropped)
    /// before the order is known. Not needed without methods.
    fn method_calls(m: &ModuleCtx, helper_items: &HashMap<String, FnDef>) -> HashMap<String, Vec<(String, Span)>> {
        let mut calls = HashMap::new();
        if !helper_items.values().any(|d| d.has_receiver) && m.generics.is_empty() {
            return calls;
        }
        for (name, def) in helper_items {
            let sig = &m.helpers[name];
            let params = lparams(&def.f, &sig.params);
            let mut l = FnLowerer::new(m, FnRole::Helper, name, sig.ret.clone());
            let _ = l.function(&sig.wgsl_name, &params, &def.f.block);
            calls.insert(name.clone(), l.method_calls);
        }
        calls
    }

    /// Lowers the helpers' bodies, callees first; helpers that trace also
    /// in their resumable form.
    pub fn lower_helpers(&mut self, m: &mut ModuleCtx, helper_items: &HashMap<String, FnDef>) {
        let method_calls = Self::method_calls(m, helper_items);
        let order = match helper_order(helper_items, &method_calls) {
            Ok(o) => o,
            Err((name, e)) => {
                self.own(&name);
                let first = self.errors.0.len();
                self.errors.push(e);
                note_instance(&mut self.errors, first, &helper_items[&name]);
                Vec::new()
            }
        };
        for name in order {
            self.own(&name);
            let f = &helper_items[&name].f;
            let sig = m.helpers[&name].clone();
            let params = lparams(f, &sig.params);
            let mut l = FnLowerer::new(m, FnRole::Helper, &name, sig.ret.clone());
            let body = l.function(&sig.wgsl_name, &params, &f.block);
            let done = l.finish(&body);
            self.typed_helpers.push((name.clone(), l.typed(&f.block)));
            let mut intr: Vec<&'static str> = l.intrinsics.iter().map(|(n, _)| *n).collect();
            intr.sort();
            intr.dedup();
            let traced = l.traced.clone();
            let first = self.errors.0.len();
            self.errors.0.extend(l.errors.0);
            note_instance(&mut self.errors, first, &helper_items[&name]);
            for (id, r) in done.ranges {
                self.source_ranges.push((sig.wgsl_name.clone(), id, r));
            }
            self.sites.push((sig.wgsl_name.clone(), done.sites));
            self.sections.push((sig.wgsl_name.clone(), done.text));
            let h = m.helpers.get_mut(&name).unwrap();
            h.intrinsics = intr;
            h.traced = traced;
            if !h.traced.is_empty() {
                let mut r = FnLowerer::new(m, FnRole::Helper, &name, sig.ret.clone());
                let rs_name = format!("{}_rs", sig.wgsl_name);
                match r.function_resumable(&rs_name, &params, &f.block) {
                    Ok(text) => {
                        let clean = r.finish(&text).text;
                        self.resumable_functions.push((rs_name, r.fill_frame_saves(&clean)));
                        m.helpers.get_mut(&name).unwrap().resumable = true;
                    }
                    Err(e) => self
                        .not_resumable_helpers
                        .push(format!("`{name}`: {}", e.message.strip_prefix("not resumable: ").unwrap_or(&e.message))),
                }
            }
        }
    }

    /// Lowers the entry if it is a program; returns the program's text.
    pub fn lower_entry(&mut self, m: &ModuleCtx, out: &mut Lowered) -> String {
        let mut program_text = String::new();
        if let Entry::Program(kind, f) = self.entry {
            out.kind = Some(*kind);
            out.name = f.sig.ident.to_string();
            out.wgsl_entry = format!("rtp_{}", f.sig.ident);
            self.owners.push((self.errors.0.len(), true));
            match program_unit(m, *kind, f, out) {
                Ok((text, ranges)) => {
                    for (id, r) in ranges {
                        self.source_ranges.push(("<program>".into(), id, r));
                    }
                    program_text = text;
                }
                Err(e) => self.errors.0.extend(e.0),
            }
        } else {
            out.name = match self.entry {
                Entry::Helper(f) => f.sig.ident.to_string(),
                Entry::Struct(s) => s.ident.to_string(),
                Entry::Const(c) => c.ident.to_string(),
                Entry::Enum(e) => e.ident.to_string(),
                Entry::Program(..) => unreachable!(),
            };
            if let Entry::Helper(f) = self.entry
                && let Some(h) = m.helpers.get(&f.sig.ident.to_string())
            {
                out.intrinsics = h.intrinsics.iter().map(|s| s.to_string()).collect();
                out.traced = h.traced.clone();
            }
        }
        program_text
    }
}

/// A helper's parameter and return types, or `None` when one is not
/// allowed (the errors say why).
fn helper_signature(m: &ModuleCtx, f: &syn::ItemFn, errors: &mut Errors) -> Option<(Vec<Ty>, Ty)> {
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
    ok.then_some((params, ret))
}

/// Names the instance in the errors from `first` on, when `def` is one: the
/// span is in the generic's body, which every instance shares.
fn note_instance(errors: &mut Errors, first: usize, def: &FnDef) {
    if let Some(what) = &def.instance {
        for e in &mut errors.0[first..] {
            if !e.is_silent() {
                e.message = format!("{} ({what})", e.message);
            }
        }
    }
}
