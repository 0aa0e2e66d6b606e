//! A program's unit: its parameters by role (payload, attributes,
//! primitive index, variables) in the canonical order the linker calls
//! every program with, its return type by kind, its body, and its
//! resumable form if it traces.

use super::func::{FnLowerer, FnRole, LParam};
use super::items::check_fn_shape;
use super::{Lowered, ModuleCtx};
use crate::StructRole;
use crate::error::{Error, Errors};
use crate::kinds::Kind;
use crate::signature::{self, Role};
use crate::types::Ty;
use syn::spanned::Spanned;

type ProgramText = (String, Vec<(usize, std::ops::Range<usize>)>);

pub(super) fn program_unit(
    m: &ModuleCtx,
    kind: Kind,
    f: &syn::ItemFn,
    out: &mut Lowered,
) -> std::result::Result<ProgramText, Errors> {
    check_fn_shape(f)?;
    let params = signature::program_params(kind, f)?;
    let mut errors = Errors::default();
    let lps = program_lparams(m, kind, f, &params, out, &mut errors);
    let ret = program_ret(m, kind, f, &mut errors);
    if kind == Kind::Callable {
        out.callable = Some(crate::types::CallSig { params: out.arguments.clone(), ret: ret.clone() });
    }
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
        // A callable's arguments keep the Rust order.
        Role::Argument => 4,
    };
    let mut order: Vec<usize> = (0..lps.len()).collect();
    order.sort_by_key(|i| rank(&params[*i]));
    let mut slots: Vec<Option<LParam>> = lps.into_iter().map(Some).collect();
    let lps: Vec<LParam> = order.into_iter().filter_map(|i| slots[i].take()).collect();
    let name = f.sig.ident.to_string();
    let mut l = FnLowerer::new(m, FnRole::Program(kind), &name, ret);
    let text = l.function(&out.wgsl_entry, &lps, &f.block);
    let done = l.finish(&text);
    out.typed = Some(l.typed(&f.block));
    out.sites.insert(out.wgsl_entry.clone(), done.sites);
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
                let clean = r.finish(&text).text;
                out.resumable = Some(r.fill_frame_saves(&clean));
            }
            Err(e) => out.not_resumable = Some(e.message),
        }
    }
    Ok((done.text, done.ranges))
}

/// The program's parameters as the lowering binds them (payload and
/// attributes by their struct roles, variables checked and recorded in
/// `out`), in the Rust order.
fn program_lparams(
    m: &ModuleCtx,
    kind: Kind,
    f: &syn::ItemFn,
    params: &[signature::Param],
    out: &mut Lowered,
    errors: &mut Errors,
) -> Vec<LParam> {
    let mut lps = Vec::new();
    for p in params {
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
            Role::Argument => {
                if let Err(e) = super::resolve::check_callable_value(&ty, p.ty.span(), "an argument") {
                    errors.push(e);
                }
                out.arguments.push(ty.clone());
                ty
            }
            Role::Variable => {
                if let Some(e) = super::resolve::host_data_error(&ty, p.ty.span(), "a variable") {
                    errors.push(e);
                    continue;
                }
                let ok = ty.is_plain_data()
                    || matches!(ty, Ty::Buffer(..) | Ty::Sampler | Ty::Sampler3d | Ty::SamplerCube | Ty::Object);
                if !ok {
                    errors.push(Error::new(
                        p.ty.span(),
                        format!("a variable cannot have type `{ty}`{}", super::resolve::store_advice(&ty)),
                    ));
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
    lps
}

/// The return type a program of `kind` must declare.
fn program_ret(m: &ModuleCtx, kind: Kind, f: &syn::ItemFn, errors: &mut Errors) -> Ty {
    match (&f.sig.output, kind) {
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
        (syn::ReturnType::Type(_, t), Kind::Callable) => match m.resolve_type(t) {
            Ok(Ty::Unit) => Ty::Unit,
            Ok(got) => {
                if let Err(e) = super::resolve::check_callable_value(&got, t.span(), "a result") {
                    errors.push(e);
                }
                got
            }
            Err(e) => {
                errors.push(e);
                Ty::Unit
            }
        },
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
    }
}
