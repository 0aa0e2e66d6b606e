//! The module put together: the stub prelude, the types, the functions
//! (accessors, constants, helpers) and the program, with the source map
//! from WGSL byte ranges to Rust spans; then validated by naga, and the
//! resumable form with it.

use super::unit::Unit;
use super::{Entry, Lowered, ModuleCtx};
use crate::error::Errors;
use proc_macro2::Span;
use std::collections::HashMap;

/// Assembles and validates the module of a unit that lowered without
/// errors.
pub(super) fn assemble(
    m: &ModuleCtx,
    entry: &Entry<'_>,
    mut unit: Unit<'_, '_>,
    mut struct_order: Vec<String>,
    program_text: String,
    mut out: Lowered,
) -> std::result::Result<Lowered, Errors> {
    let spans = m.spans.borrow().clone();
    out.prelude = prelude(m);
    // WGSL declarations are order-independent: sort for output that does not
    // depend on the order dependencies were collected in.
    struct_order.sort();
    unit.sections.sort();
    let instances = m.generic_structs.built();
    let defs = struct_order.iter().map(|name| &m.structs[name]).chain(instances.iter());
    for d in defs {
        let fields: Vec<String> =
            d.fields.iter().map(|(n, t)| format!("    {}: {},", super::resolve::wgsl_field(n), t.wgsl())).collect();
        out.types.push((d.wgsl_name.clone(), format!("struct {} {{\n{}\n}}\n", d.wgsl_name, fields.join("\n"))));
    }
    for (name, ty) in m.tuples.borrow().iter() {
        let fields: Vec<String> = ty.fields().iter().map(|(n, t)| format!("    {n}: {},", t.wgsl())).collect();
        out.types.push((name.clone(), format!("struct {name} {{\n{}\n}}\n", fields.join("\n"))));
    }
    for (name, text) in m.accessors.borrow().functions.iter() {
        out.functions.push((name.clone(), text.clone()));
    }
    out.functions.extend(unit.sections);
    out.sites.extend(unit.sites);
    out.program = program_text;
    out.typed_helpers = unit.typed_helpers;
    if out.resumable.is_some() {
        out.resumable_functions = unit.resumable_functions;
    } else if let Some(why) = &mut out.not_resumable
        && !unit.not_resumable_helpers.is_empty()
    {
        why.push_str(&format!(" ({})", unit.not_resumable_helpers.join("; ")));
    }
    out.calls = m.call_types.borrow().clone();
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
    let map: Vec<(std::ops::Range<usize>, Span)> = unit
        .source_ranges
        .iter()
        .filter_map(|(item, id, r)| {
            let base = offsets.get(item)?;
            Some((base + r.start..base + r.end, *spans.get(*id)?))
        })
        .collect();
    let fallback = match entry {
        Entry::Program(_, f) | Entry::Helper(f) => f.sig.ident.span(),
        Entry::Struct(s) => s.ident.span(),
        Entry::Const(c) => c.ident.span(),
        Entry::Enum(e) => e.ident.span(),
    };
    crate::validate::validate(&out.wgsl, &map, fallback)?;
    if let Some(r) = &out.resumable {
        // The resumable form is generated from a program that validated:
        // an error here is the compiler's, and the program falls back to
        // the plain form.
        let mut wgsl = out.wgsl[..offsets["<program>"]].to_string();
        wgsl.push_str(&resumable_stubs(m));
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

/// Stubs for everything the runtime provides. They only need the right
/// signatures: the linker replaces this whole section.
fn prelude(m: &ModuleCtx) -> String {
    let mut s = if m.accessors.borrow().atomic() { ATOMIC_PRELUDE.clone() } else { PRELUDE.clone() };
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
    for (name, sig) in m.call_types.borrow().iter() {
        s.push_str(&call_stub(name, sig));
    }
    s
}

/// A dispatch function's stub: the signature, a zero result.
fn call_stub(name: &str, sig: &crate::types::CallSig) -> String {
    let params: String = sig.params.iter().enumerate().map(|(i, t)| format!(", a{i}: {}", t.wgsl())).collect();
    match &sig.ret {
        crate::types::Ty::Unit => format!("fn {name}(id: u32{params}) {{}}\n"),
        r => format!("fn {name}(id: u32{params}) -> {0} {{\n    var r: {0};\n    return r;\n}}\n", r.wgsl()),
    }
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
pub static PRELUDE: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| rt_abi::wgsl::stub_prelude(false));

/// [`PRELUDE`] over the atomic heap, for modules that update buffer
/// elements atomically.
pub static ATOMIC_PRELUDE: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| rt_abi::wgsl::stub_prelude(true));
