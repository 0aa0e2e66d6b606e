//! A lowered program as the tokens of its `ProgramDescriptor`
//! (`rt_std::program`): its WGSL sections with the sites the linker renames,
//! the payload, attribute and variable layouts, the intrinsics, traced
//! payloads, `rt_printf!` formats and callable signatures it uses, its CPU
//! entries, file and line. A program whose lowering failed gets its errors
//! and a descriptor of the same type, so the code around it compiles.

use crate::error::Errors;
use crate::kinds::Kind;
use crate::lower::Lowered;
use crate::lower::text::Site;
use crate::types::Ty;
use proc_macro2::TokenStream;
use quote::{format_ident, quote, quote_spanned};
use std::collections::BTreeMap;

fn str_slice(items: &[String]) -> TokenStream {
    quote!(&[#(#items),*])
}

/// `LayoutKind` tokens for a type: what the runtime matches instead of
/// the type's spelling.
pub(super) fn layout_kind(ty: &Ty) -> TokenStream {
    let scalar = |s: &crate::types::Scalar| match s {
        crate::types::Scalar::F32 => quote!(::rt_std::program::ScalarKind::F32),
        crate::types::Scalar::U32 | crate::types::Scalar::Usize => quote!(::rt_std::program::ScalarKind::U32),
        crate::types::Scalar::I32 => quote!(::rt_std::program::ScalarKind::I32),
        crate::types::Scalar::Bool => quote!(::rt_std::program::ScalarKind::Bool),
    };
    let kind = match ty {
        Ty::Unit | Ty::Never => quote!(Unit),
        Ty::Scalar(s) => {
            let s = scalar(s);
            quote!(Scalar(#s))
        }
        Ty::IntVar(_) => quote!(Scalar(::rt_std::program::ScalarKind::I32)),
        Ty::Vec(n, s) => {
            let s = scalar(s);
            quote!(Vector { scalar: #s, len: #n })
        }
        Ty::Mat(n) => quote!(Matrix(#n)),
        Ty::Struct(_) => quote!(Struct),
        Ty::Enum(_) => quote!(Enum),
        // A struct of a flag and a value (never in a layout the host reads).
        Ty::Tuple(_) | Ty::Option(_) => quote!(Tuple),
        Ty::Array(_, n) => quote!(Array(#n)),
        Ty::Ray | Ty::Aabb => quote!(Builtin),
        Ty::Callable(sig) => {
            let sig = signature_tokens(sig);
            quote!(Callable(Some(&#sig)))
        }
        Ty::BufferId(writable, element) => {
            let element = layout(element);
            quote!(BufferId { writable: #writable, element: Some(&#element) })
        }
        Ty::SamplerId(shape) => {
            let shape = match **shape {
                Ty::Sampler3d => quote!(Volume),
                Ty::SamplerCube => quote!(Cube),
                _ => quote!(Flat),
            };
            quote!(SamplerId(Some(::rt_std::program::SamplerKind::#shape)))
        }
        Ty::Ref(_, t) => return layout_kind(t),
        Ty::Object | Ty::TransformKind | Ty::Buffer(..) | Ty::Sampler | Ty::Sampler3d | Ty::SamplerCube => {
            quote!(Handle)
        }
    };
    quote!(::rt_std::program::LayoutKind::#kind)
}

/// `TypeLayout` tokens for a type.
fn layout(ty: &Ty) -> TokenStream {
    let kind = layout_kind(ty);
    let rust = ty.rust();
    let wgsl = ty.wgsl();
    let words = ty.words();
    let mut offset = 0u32;
    let fields: Vec<TokenStream> = ty
        .fields()
        .into_iter()
        .map(|(n, t)| {
            let tr = t.rust();
            let o = offset;
            offset += t.words();
            let kind = layout_kind(&t);
            quote!(::rt_std::program::FieldLayout { name: #n, ty: #tr, kind: #kind, offset_words: #o })
        })
        .collect();
    quote!(::rt_std::program::TypeLayout { kind: #kind, rust: #rust, wgsl: #wgsl, words: #words, fields: &[#(#fields),*] })
}

fn option_layout(ty: &Option<Ty>) -> TokenStream {
    match ty {
        Some(t) => {
            let l = layout(t);
            quote!(Some(#l))
        }
        None => quote!(None),
    }
}

/// `WgslItem` tokens, with the sites the lowering recorded for each (none
/// for types and resumable forms).
fn wgsl_items(items: &[(String, String)], sites: &BTreeMap<String, Vec<(Site, usize)>>) -> TokenStream {
    let items = items.iter().map(|(n, t)| {
        let s = wgsl_sites(sites.get(n).map_or(&[], Vec::as_slice));
        quote!(::rt_std::program::WgslItem { name: #n, text: #t, sites: #s })
    });
    quote!(&[#(#items),*])
}

/// `CallableSignature` tokens.
fn signature_tokens(sig: &crate::types::CallSig) -> TokenStream {
    let rust = sig.rust();
    let dispatch = sig.dispatch();
    let params: Vec<String> = sig.params.iter().map(Ty::wgsl).collect();
    let params = str_slice(&params);
    let ret = match &sig.ret {
        Ty::Unit => quote!(None),
        r => {
            let w = r.wgsl();
            quote!(Some(#w))
        }
    };
    quote!(::rt_std::program::CallableSignature { rust: #rust, dispatch: #dispatch, params: #params, ret: #ret })
}

/// `WgslSite` tokens.
fn wgsl_sites(sites: &[(Site, usize)]) -> TokenStream {
    let sites = sites.iter().map(|(s, end)| {
        let end = *end as u32;
        let name = match s {
            Site::Definition => quote!(Definition),
            Site::Trace(p) => quote!(Trace(#p)),
            Site::Call(h) => quote!(Call(#h)),
            Site::Dispatch(d) => quote!(Dispatch(#d)),
        };
        quote!(::rt_std::program::WgslSite { end: #end, name: ::rt_std::program::WgslName::#name })
    });
    quote!(&[#(#sites),*])
}

pub(super) fn program_output(kind: Kind, f: &syn::ItemFn, lowered: Result<Lowered, Errors>) -> TokenStream {
    // The lane-wise form only where the program lowered: one that did not
    // has its errors already, and a second copy of its body would repeat
    // rustc's.
    let lanes = match &lowered {
        Ok(_) => crate::lanes::lane_form(kind, f),
        Err(_) => quote! {
            const CPU_LANES: ::rt_std::program::CpuLanes = ::rt_std::program::CpuLanes::Scalar("the program has errors");
        },
    };
    let (errors, l) = match lowered {
        Ok(l) => (TokenStream::new(), l),
        Err(e) => (e.to_compile_errors(), Lowered { name: f.sig.ident.to_string(), ..Lowered::default() }),
    };
    let variant = format_ident!("{}", kind.variant());
    let name = f.sig.ident.to_string();
    let wgsl_entry = format!("rtp_{name}");
    let wgsl = &l.wgsl;
    let prelude = &l.prelude;
    let no_sites = BTreeMap::new();
    let types = wgsl_items(&l.types, &no_sites);
    let functions = wgsl_items(&l.functions, &l.sites);
    let resumable_functions = wgsl_items(&l.resumable_functions, &no_sites);
    let program = &l.program;
    let program_sites = wgsl_sites(l.sites.get(&l.wgsl_entry).map_or(&[], Vec::as_slice));
    let resumable = match &l.resumable {
        Some(r) => quote!(Some(#r)),
        None => quote!(None),
    };
    let not_resumable = match &l.not_resumable {
        Some(why) => quote!(Some(#why)),
        None => quote!(None),
    };
    let payload = option_layout(&l.payload);
    let attributes = option_layout(&l.attributes);
    let variables = l.variables.iter().map(|(n, t)| {
        let lay = layout(t);
        let vkind = match t {
            Ty::Buffer(k, e) => {
                let el = layout(e);
                let dims = k.dims as u32;
                let w = k.writable;
                quote!(::rt_std::program::VariableKind::Buffer { element: #el, dimensions: #dims, writable: #w })
            }
            Ty::Sampler => quote!(::rt_std::program::VariableKind::Sampler),
            Ty::Sampler3d => quote!(::rt_std::program::VariableKind::Sampler3d),
            Ty::SamplerCube => quote!(::rt_std::program::VariableKind::SamplerCube),
            Ty::Object => quote!(::rt_std::program::VariableKind::Object),
            _ => quote!(::rt_std::program::VariableKind::Value),
        };
        let loader = match t {
            Ty::Buffer(..) => "rt_load_RtBuffer".to_string(),
            Ty::Sampler | Ty::SamplerCube => "rt_load_RtSampler".to_string(),
            Ty::Sampler3d => "rt_load_RtSampler3d".to_string(),
            Ty::Object => "rt_load_object".to_string(),
            other => format!("rt_load_{}", other.mangle()),
        };
        quote!(::rt_std::program::VariableDescriptor { name: #n, ty: #lay, kind: #vkind, wgsl_load: #loader })
    });
    let intrinsics = str_slice(&l.intrinsics);
    let traced = l.traced.iter().map(layout);
    let printf = l.printf.iter().map(|(id, fmt, args)| {
        let args = str_slice(args);
        quote!(::rt_std::program::PrintfFormat { id: #id, format: #fmt, args: #args })
    });
    let has_attributes = f.sig.inputs.iter().any(|i| {
        matches!(i, syn::FnArg::Typed(pt) if matches!(&*pt.ty, syn::Type::Reference(_))
            && matches!(kind, Kind::ClosestHit | Kind::AnyHit | Kind::Intersection)
            && (kind == Kind::Intersection || matches!(&*pt.ty, syn::Type::Reference(r) if r.mutability.is_none())))
    });
    let cpu_attributes = if has_attributes { quote!(Some(attributes_from_words)) } else { quote!(None) };
    let calls = l.calls.values().map(|s| signature_tokens(s));
    let callable = match &l.callable {
        Some(sig) => {
            let sig = signature_tokens(sig);
            quote!(Some(::rt_std::program::CallableDescriptor { signature: #sig, cpu: &CALLABLE }))
        }
        None => quote!(None),
    };
    let span = f.sig.ident.span();
    let file = quote_spanned!(span=> file!());
    let line = quote_spanned!(span=> line!());
    quote! {
        {
        #errors
        #lanes
        ::rt_std::program::ProgramDescriptor {
            kind: ::rt_std::program::ProgramKind::#variant,
            name: #name,
            wgsl_entry: #wgsl_entry,
            wgsl: #wgsl,
            wgsl_prelude: #prelude,
            wgsl_types: #types,
            wgsl_functions: #functions,
            wgsl_program: #program,
            wgsl_program_sites: #program_sites,
            wgsl_resumable: #resumable,
            wgsl_resumable_functions: #resumable_functions,
            not_resumable: #not_resumable,
            payload: #payload,
            attributes: #attributes,
            variables: &[#(#variables),*],
            intrinsics: #intrinsics,
            traced_payloads: &[#(#traced),*],
            printf: &[#(#printf),*],
            calls: &[#(#calls),*],
            callable: #callable,
            file: #file,
            line: #line,
            cpu: cpu,
            cpu_bind: cpu_bind,
            cpu_attributes: #cpu_attributes,
            cpu_lanes: CPU_LANES,
        }
        }
    }
}
