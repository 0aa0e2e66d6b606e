//! The glam methods and associated functions programs may call, checked
//! against glam's own API and published as `docs/glam_methods.md`
//! (`RT_BLESS=1` rewrites it).
//!
//! glam's API is read from its source (the version in `Cargo.lock`, in
//! cargo's registry): every `pub fn` of an inherent `impl` of `Vec2/3/4`,
//! `IVec2/3/4`, `UVec2/3/4`, `BVec2/3/4` and `Mat2/3/4`, methods (a `self`
//! receiver) and associated functions (`Vec3::new`, `Mat3::from_cols`)
//! counted apart. For each, the compiler's own tables
//! (`rt_compiler::lower::builtins::method_sig`, `in_place_method` and
//! `assoc_fn`) say whether programs may call it; a supported one whose
//! parameter or result types differ from glam's fails the test. The scalar
//! types' methods are std's, not glam's, and are not counted here (std's
//! source is not in cargo's registry).

use rt_compiler::types::{Scalar, Ty};
use std::path::{Path, PathBuf};

/// The types, their glam source files (the scalar, not SIMD, forms).
const TYPES: &[(&str, &str)] = &[
    ("Vec2", "f32/vec2.rs"),
    ("Vec3", "f32/vec3.rs"),
    ("Vec4", "f32/scalar/vec4.rs"),
    ("IVec2", "i32/ivec2.rs"),
    ("IVec3", "i32/ivec3.rs"),
    ("IVec4", "i32/ivec4.rs"),
    ("UVec2", "u32/uvec2.rs"),
    ("UVec3", "u32/uvec3.rs"),
    ("UVec4", "u32/uvec4.rs"),
    ("BVec2", "bool/bvec2.rs"),
    ("BVec3", "bool/bvec3.rs"),
    ("BVec4", "bool/bvec4.rs"),
    ("Mat2", "f32/scalar/mat2.rs"),
    ("Mat3", "f32/mat3.rs"),
    ("Mat4", "f32/scalar/mat4.rs"),
];

/// glam's source directory, from `Cargo.lock`'s version and cargo's home.
fn glam_src() -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let lock = std::fs::read_to_string(root.join("Cargo.lock")).expect("Cargo.lock");
    let version = lock
        .split("[[package]]")
        .find(|p| p.contains("name = \"glam\""))
        .and_then(|p| p.lines().find_map(|l| l.strip_prefix("version = \"")))
        .map(|v| v.trim_end_matches('"').to_string())
        .expect("glam in Cargo.lock");
    let home = std::env::var_os("CARGO_HOME")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(std::env::var_os("HOME").expect("HOME")).join(".cargo"));
    let registry = home.join("registry/src");
    for index in std::fs::read_dir(&registry).unwrap_or_else(|e| panic!("{}: {e}", registry.display())) {
        let dir = index.unwrap().path().join(format!("glam-{version}/src"));
        if dir.is_dir() {
            return dir;
        }
    }
    panic!("glam {version}'s source is not in {}", registry.display());
}

/// A glam method: name, parameter types and result type as written
/// (`Self` replaced by the type's name, references dropped).
struct GlamMethod {
    name: String,
    params: Vec<String>,
    ret: String,
    /// Has type parameters (`map<F: Fn..>`).
    generic: bool,
    /// Takes `self` (a method), else an associated function.
    method: bool,
}

fn spell(ty: &syn::Type, owner: &str) -> String {
    let t = match ty {
        syn::Type::Reference(r) => &*r.elem,
        t => t,
    };
    let s = quote::ToTokens::to_token_stream(t).to_string().replace(' ', "").replace("crate::", "");
    // `Self` alone or inside a tuple (`(Self,f32)`), as the owner's name.
    let mut out = String::new();
    let mut rest = s.as_str();
    while let Some(i) = rest.find("Self") {
        let before = rest[..i].chars().next_back();
        let after = rest[i + 4..].chars().next();
        let ident = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
        out.push_str(&rest[..i]);
        out.push_str(if ident(before) || ident(after) { "Self" } else { owner });
        rest = &rest[i + 4..];
    }
    out.push_str(rest);
    out
}

fn glam_methods(owner: &str, file: &Path) -> Vec<GlamMethod> {
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let ast: syn::File = syn::parse_str(&text).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let mut out = Vec::new();
    for item in &ast.items {
        let syn::Item::Impl(imp) = item else { continue };
        let is_owner = matches!(&*imp.self_ty, syn::Type::Path(p) if p.path.is_ident(owner));
        if imp.trait_.is_some() || !is_owner {
            continue;
        }
        for it in &imp.items {
            let syn::ImplItem::Fn(f) = it else { continue };
            if !matches!(f.vis, syn::Visibility::Public(_)) {
                continue;
            }
            let params = f
                .sig
                .inputs
                .iter()
                .filter_map(|i| match i {
                    syn::FnArg::Typed(pt) => Some(spell(&pt.ty, owner)),
                    syn::FnArg::Receiver(_) => None,
                })
                .collect();
            let ret = match &f.sig.output {
                syn::ReturnType::Default => "()".to_string(),
                syn::ReturnType::Type(_, t) => spell(t, owner),
            };
            let generic = !f.sig.generics.params.is_empty();
            let method = f.sig.receiver().is_some();
            out.push(GlamMethod { name: f.sig.ident.to_string(), params, ret, generic, method });
        }
    }
    out
}

/// Why a glam method has no WGSL meaning in the subset, from its signature.
fn reason(m: &GlamMethod) -> &'static str {
    let all: Vec<&str> = m.params.iter().map(String::as_str).chain([m.ret.as_str()]).collect();
    let any = |f: &dyn Fn(&str) -> bool| all.iter().any(|t| f(t));
    if m.ret.starts_with("Option") {
        "returns `Option`"
    } else if any(&|t| t.contains("f64") || t.starts_with("DVec") || t.starts_with("DMat")) {
        "f64"
    } else if any(&|t| {
        ["I64", "U64", "I16", "U16", "I8", "U8", "i64", "u64", "i16", "u16", "i8", "u8", "isize"]
            .iter()
            .any(|p| t.contains(p))
    }) {
        "64/16/8-bit integers"
    } else if any(&|t| t.starts_with("BVec")) {
        "bool vectors (`BVec`)"
    } else if any(&|t| t.contains("[f32]") || t.contains("[i32]") || t.contains("[u32]")) && m.name.starts_with("write")
    {
        "writes into a slice (`&mut [T]`), which ray programs cannot have; use `to_array`/`to_cols_array`"
    } else if any(&|t| t.contains("[f32]") || t.contains("[i32]") || t.contains("[u32]")) {
        "reads a slice (`&[T]`), which ray programs cannot have; use `from_array`/`from_cols_array`"
    } else if m.name.ends_with("_minor") {
        "not written out yet: glam panics for a row or column past the end, which needs a clamping CPU copy"
    } else if any(&|t| t.starts_with('[')) {
        "arrays"
    } else if any(&|t| t.contains("Quat") || t.contains("Affine") || t.contains("Vec3A") || t.contains("Mat3A")) {
        "Quat, Affine and SIMD types are not in the subset"
    } else if m.generic || any(&|t| t.contains("impl") || t.contains("Fn")) {
        "takes a closure"
    } else if any(&|t| t.contains("SizeVec")) {
        "isize/usize vectors"
    } else if any(&|t| t.contains("EulerRot")) {
        "takes `EulerRot`, not in the subset"
    } else {
        "not written out yet"
    }
}

fn ty_of(name: &str) -> Ty {
    match name {
        "Vec2" => Ty::Vec(2, Scalar::F32),
        "Vec3" => Ty::Vec(3, Scalar::F32),
        "Vec4" => Ty::Vec(4, Scalar::F32),
        "IVec2" => Ty::Vec(2, Scalar::I32),
        "IVec3" => Ty::Vec(3, Scalar::I32),
        "IVec4" => Ty::Vec(4, Scalar::I32),
        "UVec2" => Ty::Vec(2, Scalar::U32),
        "UVec3" => Ty::Vec(3, Scalar::U32),
        "UVec4" => Ty::Vec(4, Scalar::U32),
        "BVec2" => Ty::Vec(2, Scalar::Bool),
        "BVec3" => Ty::Vec(3, Scalar::Bool),
        "BVec4" => Ty::Vec(4, Scalar::Bool),
        "Mat2" => Ty::Mat(2),
        "Mat3" => Ty::Mat(3),
        _ => Ty::Mat(4),
    }
}

#[test]
fn supported_glam_methods_have_glam_signatures_and_the_table_is_current() {
    use rt_compiler::lower::builtins::{assoc_fn, in_place_method, method_sig};
    let src = glam_src();
    let mut doc = String::from(
        "# glam methods in ray programs\n\n\
         Generated by `tests/tests/glam_coverage.rs` from the compiler's tables and glam's source \
         (`RT_BLESS=1 cargo test -p rt-tests --test glam_coverage` rewrites it). Counted: every public \
         function of an inherent `impl` of the type in glam, methods (a `self` receiver) and associated \
         functions apart; std's scalar methods are not counted.\n\n",
    );
    let mut mismatches = Vec::new();
    // (supported, total) of methods and of associated functions.
    let mut counts = [(0, 0), (0, 0)];
    let mut sections = String::new();
    for (owner, file) in TYPES {
        let ty = ty_of(owner);
        let all = glam_methods(owner, &src.join(file));
        sections.push_str(&format!("## {owner}\n\n"));
        for (k, (what, methods)) in [("Methods", true), ("Associated functions", false)].into_iter().enumerate() {
            let mut yes = Vec::new();
            let mut no = Vec::new();
            for m in all.iter().filter(|m| m.method == methods) {
                // The expression methods, then those that change the value
                // in place (`set_row`, `col_mut`: a `&mut` result is
                // spelled as its target, as glam's is here).
                let found = if m.method {
                    method_sig(&ty, &m.name).map(|sig| (sig.params, sig.ret)).or_else(|| {
                        in_place_method(&ty, &m.name).map(|(params, ret)| match ret {
                            Ty::Ref(_, t) => (params, *t),
                            t => (params, t),
                        })
                    })
                } else {
                    assoc_fn(&ty, &m.name).map(|sig| (sig.params, sig.ret))
                };
                let Some((params, sig_ret)) = found else {
                    no.push(format!("`{}` ({})", m.name, reason(m)));
                    continue;
                };
                // (glam's spelling has no spaces: `[f32;3]`.)
                let ours: Vec<String> = params.iter().map(|t| t.to_string().replace(' ', "")).collect();
                let ret = match &sig_ret {
                    Ty::Tuple(ts) => format!("({})", ts.iter().map(Ty::to_string).collect::<Vec<_>>().join(",")),
                    t => t.to_string().replace(' ', ""),
                };
                // `BVec4A` is `Vec4`'s mask where glam's `Vec4` is SIMD; the
                // subset spells both `BVec4`.
                let glam_params: Vec<String> = m.params.iter().map(|p| p.replace("BVec4A", "BVec4")).collect();
                if ours != glam_params || ret != m.ret.replace("BVec4A", "BVec4") {
                    mismatches.push(format!(
                        "{owner}::{}: glam ({}) -> {}, ours ({}) -> {ret}",
                        m.name,
                        m.params.join(", "),
                        m.ret,
                        ours.join(", ")
                    ));
                }
                yes.push(m.name.clone());
            }
            counts[k].0 += yes.len();
            counts[k].1 += yes.len() + no.len();
            sections.push_str(&format!(
                "{what}: {} of {}\n\nSupported: {}\n\nLeft out: {}\n\n",
                yes.len(),
                yes.len() + no.len(),
                if yes.is_empty() {
                    "none".to_string()
                } else {
                    yes.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
                },
                if no.is_empty() { "none".to_string() } else { no.join(", ") }
            ));
        }
    }
    let [(m_yes, m_all), (a_yes, a_all)] = counts;
    doc.push_str(&format!(
        "**{m_yes} of {m_all} methods and {a_yes} of {a_all} associated functions supported.**\n\n{sections}"
    ));
    assert!(mismatches.is_empty(), "signatures that differ from glam's:\n{}", mismatches.join("\n"));
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/glam_methods.md");
    if std::env::var_os("RT_BLESS").is_some() {
        std::fs::write(&path, &doc).unwrap();
    }
    let current = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(current == doc, "docs/glam_methods.md is out of date (RT_BLESS=1 to rewrite it)");
}
