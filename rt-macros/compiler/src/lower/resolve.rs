//! Rust types and names as WGSL sees them: the subset's types resolved
//! from syn's, and the identifiers that must be renamed because WGSL
//! reserves them.

use crate::error::{Error, Result};
use crate::types::{self, Ty};
use syn::Expr;
use syn::spanned::Spanned;

/// What resolving a type asks of the unit: the user type `name` names
/// (a struct or enum), with its generic arguments (`None` where written
/// without), `None` where the unit has no type of that name; the span is
/// the use's.
pub type UserTypes<'a> = dyn Fn(&str, Option<&[Ty]>, proc_macro2::Span) -> Option<Result<Ty>> + 'a;

/// `BindlessSampler<S>`: `S` one of the sampler types.
fn resolve_sampler_id(seg: &syn::PathSegment, user: &UserTypes<'_>) -> Result<Ty> {
    let want = "`BindlessSampler` takes a sampler type: `BindlessSampler<Sampler2d>`, `<Sampler3d>` or `<SamplerCube>`";
    let arg = match &seg.arguments {
        syn::PathArguments::AngleBracketed(a) if a.args.len() == 1 => match &a.args[0] {
            syn::GenericArgument::Type(t) => t,
            other => return Err(Error::new(other.span(), want)),
        },
        _ => return Err(Error::new(seg.span(), want)),
    };
    match resolve_type(arg, user)? {
        shape @ (Ty::Sampler | Ty::Sampler3d | Ty::SamplerCube) => Ok(Ty::SamplerId(Box::new(shape))),
        other => Err(Error::new(arg.span(), format!("{want}, found `{other}`"))),
    }
}

/// Resolves a Rust type in the subset; `user` looks up user structs.
pub fn resolve_type(ty: &syn::Type, user: &UserTypes<'_>) -> Result<Ty> {
    match ty {
        syn::Type::Path(p) => {
            if p.qself.is_some() {
                return Err(Error::unsupported(p.span(), "a qualified type", "name the type directly"));
            }
            let seg = p.path.segments.last().unwrap();
            let name = seg.ident.to_string();
            let bindless = types::bindless_kind(&name);
            let buffer = types::buffer_kind(&name);
            if bindless.is_some() || buffer.is_some() {
                let arg = match &seg.arguments {
                    syn::PathArguments::AngleBracketed(a) if a.args.len() == 1 => match &a.args[0] {
                        syn::GenericArgument::Type(t) => t,
                        other => return Err(Error::new(other.span(), format!("`{name}` takes an element type"))),
                    },
                    _ => return Err(Error::new(seg.span(), format!("`{name}` takes one element type: `{name}<T>`"))),
                };
                let elem = resolve_type(arg, user)?;
                if let Some(e) = host_data_error(&elem, arg.span(), "a buffer element") {
                    return Err(e);
                }
                if !elem.is_plain_data() {
                    return Err(Error::new(
                        arg.span(),
                        format!("`{elem}` cannot be a buffer element{}", store_advice(&elem)),
                    ));
                }
                return Ok(match (buffer, bindless) {
                    (Some(kind), _) => Ty::Buffer(kind, Box::new(elem)),
                    (None, writable) => Ty::BufferId(writable == Some(true), Box::new(elem)),
                });
            }
            if name == "Callable" {
                return resolve_callable(seg, user);
            }
            if name == types::BINDLESS_SAMPLER {
                return resolve_sampler_id(seg, user);
            }
            if name == "Option" {
                return resolve_option(seg, user);
            }
            // Before the generic arguments: `Vec<f32>` is a heap type.
            if let Some(advice) = types::unsupported_type_advice(&name) {
                return Err(Error::unsupported(seg.ident.span(), &format!("the type `{name}`"), advice));
            }
            if !seg.arguments.is_none() {
                return resolve_instance(&name, seg, p.span(), user);
            }
            if let Some(t) = types::builtin_type(&name) {
                return Ok(t);
            }
            if let Some(t) = user(&name, None, p.span()) {
                return t;
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
            let n = array_len(&a.len)?;
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
            let mut elems = Vec::new();
            for e in &t.elems {
                let ty = resolve_type(e, user)?;
                check_tuple_element(&ty, e.span())?;
                elems.push(ty);
            }
            Ok(Ty::Tuple(elems))
        }
        syn::Type::Paren(p) => resolve_type(&p.elem, user),
        syn::Type::Slice(s) => {
            Err(Error::unsupported(s.span(), "a slice", "use a fixed-size array or a buffer variable"))
        }
        syn::Type::Ptr(p) => Err(Error::unsupported(p.span(), "a raw pointer", "use `&mut` parameters")),
        syn::Type::TraitObject(t) => Err(Error::unsupported(
            t.span(),
            "a trait object (`dyn`)",
            "traits dispatch statically in ray programs: take a type parameter (`fn f<T: Trait>(x: T)`); \
             to choose the code at run time, call a callable program through a `Callable` id",
        )),
        syn::Type::ImplTrait(t) => Err(Error::unsupported(
            t.span(),
            "`impl Trait`",
            "name a type parameter (`fn f<T: Trait>(x: T)`) or a concrete type",
        )),
        syn::Type::BareFn(f) => {
            Err(Error::unsupported(f.span(), "a function pointer", "WGSL has no function pointers"))
        }
        syn::Type::Never(n) => Err(Error::unsupported(n.span(), "the never type", "return a value")),
        other => {
            Err(Error::unsupported(other.span(), "this type", "use scalars, glam types, arrays and #[rt_struct]s"))
        }
    }
}

/// `Name<A, ..>` of a user type (`seg` its last segment, `span` the
/// whole path's): a generic struct's instance, if `Name` is one.
fn resolve_instance(name: &str, seg: &syn::PathSegment, span: proc_macro2::Span, user: &UserTypes<'_>) -> Result<Ty> {
    if types::builtin_type(name).is_none()
        && let syn::PathArguments::AngleBracketed(a) = &seg.arguments
    {
        let mut args = Vec::new();
        for g in &a.args {
            match g {
                syn::GenericArgument::Type(t) => args.push(resolve_type(t, user)?),
                other => {
                    return Err(Error::unsupported(
                        other.span(),
                        "this generic argument",
                        "a generic struct takes types: `Pair<f32>`",
                    ));
                }
            }
        }
        if let Some(t) = user(name, Some(&args), span) {
            return t;
        }
    }
    Err(Error::unsupported(seg.arguments.span(), "generic type arguments", "use concrete types"))
}

/// What to store instead of a value that cannot be stored, where there is
/// one: a bool vector's bits (WGSL's bools have no layout in memory the
/// host shares), an `Option`'s flag and value.
pub fn store_advice(ty: &Ty) -> String {
    match ty {
        Ty::Option(t) => format!(
            ": an `Option` has no memory layout the host shares; store a flag and a value (`hit: bool, value: {t}`, or a sentinel value) and rebuild it with `if hit {{ Some(value) }} else {{ None }}`"
        ),
        Ty::Vec(_, types::Scalar::Bool) => {
            format!(
                ": a bool vector has no memory layout the host shares; store `mask.bitmask()` (a `u32`) and rebuild it with `{ty}::new(bits & 1 != 0, ..)`"
            )
        }
        _ => String::new(),
    }
}

/// `Option<T>` of a value a tuple may hold (scalars, vectors, matrices,
/// arrays, structs, enums, tuples, ids).
fn resolve_option(seg: &syn::PathSegment, user: &UserTypes<'_>) -> Result<Ty> {
    let arg = match &seg.arguments {
        syn::PathArguments::AngleBracketed(a) if a.args.len() == 1 => match &a.args[0] {
            syn::GenericArgument::Type(t) => t,
            other => return Err(Error::new(other.span(), "`Option` takes a type: `Option<f32>`")),
        },
        _ => return Err(Error::new(seg.span(), "`Option` takes one type: `Option<f32>`")),
    };
    let elem = resolve_type(arg, user)?;
    let ok = match &elem {
        Ty::Scalar(_) | Ty::Option(_) => true,
        Ty::Tuple(ts) => ts.iter().all(|t| !matches!(t, Ty::Unit)),
        t => t.is_plain_data(),
    };
    if !ok {
        return Err(Error::unsupported(
            arg.span(),
            &format!("`Option<{elem}>`"),
            "an `Option` holds a plain value (a scalar, vector, matrix, array, struct, enum or tuple); keep handles and references apart and pass a flag beside them",
        ));
    }
    Ok(Ty::Option(Box::new(elem)))
}

/// `Callable<fn(A, ..) -> R>`: arguments and result of plain values.
fn resolve_callable(seg: &syn::PathSegment, user: &UserTypes<'_>) -> Result<Ty> {
    let shape = "`Callable` takes a function type: `Callable<fn(Vec3, Vec3) -> Vec3>`";
    let f = match &seg.arguments {
        syn::PathArguments::AngleBracketed(a) if a.args.len() == 1 => match &a.args[0] {
            syn::GenericArgument::Type(syn::Type::BareFn(f)) => f,
            other => return Err(Error::new(other.span(), shape)),
        },
        _ => return Err(Error::new(seg.span(), shape)),
    };
    if let Some(v) = &f.variadic {
        return Err(Error::unsupported(v.span(), "a variadic callable", "list the arguments"));
    }
    let mut params = Vec::new();
    for a in &f.inputs {
        let ty = resolve_type(&a.ty, user)?;
        check_callable_value(&ty, a.ty.span(), "an argument")?;
        params.push(ty);
    }
    let ret = match &f.output {
        syn::ReturnType::Default => Ty::Unit,
        syn::ReturnType::Type(_, t) => {
            let ty = resolve_type(t, user)?;
            if ty != Ty::Unit {
                check_callable_value(&ty, t.span(), "a result")?;
            }
            ty
        }
    };
    Ok(Ty::Callable(std::rc::Rc::new(types::CallSig { params, ret })))
}

/// What a callable program takes and returns: plain values (scalars,
/// vectors, matrices, arrays, structs, enums, tuples, callable ids).
pub fn check_callable_value(ty: &Ty, span: proc_macro2::Span, what: &str) -> Result<()> {
    if let Some(e) = host_data_error(ty, span, &format!("{what} of a callable")) {
        return Err(e);
    }
    if matches!(ty, Ty::Scalar(_)) || ty.is_plain_data() {
        return Ok(());
    }
    let advice = match ty {
        Ty::Ref(..) => {
            "callables take their arguments by value and return results; pass the value and use what it returns"
        }
        _ => {
            "callables take and return plain values (scalars, vectors, matrices, arrays, structs, enums, tuples); read handles in the caller"
        }
    };
    Err(Error::unsupported(span, &format!("`{ty}` as {what} of a callable"), advice))
}

/// A tuple holds plain values (scalars, vectors, matrices, arrays,
/// structs, enums, tuples): not handles, references or `()`.
pub fn check_tuple_element(ty: &Ty, span: proc_macro2::Span) -> Result<()> {
    let ok = match ty {
        Ty::Scalar(_) | Ty::Option(_) => true,
        Ty::Tuple(ts) => ts.iter().all(|t| !matches!(t, Ty::Unit)),
        t => t.is_plain_data(),
    };
    if ok {
        Ok(())
    } else {
        Err(Error::unsupported(
            span,
            &format!("a tuple of `{ty}`"),
            "tuples hold plain values (scalars, vectors, matrices, arrays, structs, enums); pass handles and references as parameters of their own",
        ))
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
/// A struct field's WGSL name: a tuple struct's `0` is `f0` (as a tuple's
/// element is), any other field's its identifier made safe.
pub fn wgsl_field(name: &str) -> String {
    if name.starts_with(|c: char| c.is_ascii_digit()) { format!("f{name}") } else { wgsl_ident(name) }
}

pub fn wgsl_ident(name: &str) -> String {
    if is_reserved(name) || name.starts_with("rt") || name.starts_with("Rt") || name.starts_with("__") {
        format!("{name}_")
    } else {
        name.to_string()
    }
}

/// The length of an array type or repeat expression: a literal, not zero.
pub fn array_len(e: &Expr) -> Result<u32> {
    match e {
        Expr::Lit(syn::ExprLit { lit: syn::Lit::Int(i), .. }) => {
            let n: u32 = i.base10_parse()?;
            if n == 0 {
                return Err(Error::unsupported(i.span(), "a zero-length array", "arrays need at least one element"));
            }
            Ok(n)
        }
        other => Err(Error::unsupported(other.span(), "a non-literal array length", "write the length as a number")),
    }
}

/// The error for an instance of a generic struct (inside `ty`) where the
/// host reads or writes the value (`what`: "a buffer element", ...), if
/// there is one in it (see `generic_structs`).
pub fn host_data_error(ty: &Ty, span: proc_macro2::Span, what: &str) -> Option<Error> {
    let inst = ty.generic_instance()?;
    let (name, _) = inst.generic.as_ref()?;
    Some(Error::unsupported(
        span,
        &format!("`{}` (an instance of the generic struct `{name}`) as {what}", inst.name),
        &format!(
            "the host reads and writes it by a layout, and a generic struct has none: declare a struct with \
             concrete fields for it (`struct {name}F32 {{ .. }}`); a generic struct lives inside programs and helpers"
        ),
    ))
}
