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

/// std's methods and associated functions of the scalar types, as listed
/// in std's documentation for the toolchain this builds with (std's source
/// is not in cargo's registry to be read as glam's is): every stable
/// inherent function, `(name, why it is left out)` where it has no WGSL
/// meaning in the subset. A supported one's signature is checked by rustc:
/// `tests/src/std_signatures.rs`, generated here from the compiler's table,
/// is compiled with the tests (`RT_BLESS=1` rewrites it).
/// A scalar type: its name, the functions counted, and those left out with
/// why.
type StdType = (&'static str, &'static [&'static str], &'static [(&'static str, &'static str)]);

const STD: &[StdType] = &[
    (
        "f32",
        &[
            "abs",
            "signum",
            "copysign",
            "floor",
            "ceil",
            "round",
            "round_ties_even",
            "trunc",
            "fract",
            "mul_add",
            "div_euclid",
            "rem_euclid",
            "powi",
            "powf",
            "sqrt",
            "exp",
            "exp2",
            "exp_m1",
            "ln",
            "log",
            "log2",
            "log10",
            "ln_1p",
            "cbrt",
            "hypot",
            "sin",
            "cos",
            "tan",
            "asin",
            "acos",
            "atan",
            "atan2",
            "sin_cos",
            "sinh",
            "cosh",
            "tanh",
            "asinh",
            "acosh",
            "atanh",
            "is_nan",
            "is_infinite",
            "is_finite",
            "is_subnormal",
            "is_normal",
            "is_sign_positive",
            "is_sign_negative",
            "next_up",
            "next_down",
            "recip",
            "to_degrees",
            "to_radians",
            "max",
            "min",
            "midpoint",
            "to_bits",
            "clamp",
            "from_bits",
        ],
        &[
            ("classify", "returns `FpCategory`"),
            ("total_cmp", "returns `Ordering`"),
            ("to_int_unchecked", "unsafe"),
            ("to_be_bytes", "byte arrays (`[u8; 4]`)"),
            ("to_le_bytes", "byte arrays (`[u8; 4]`)"),
            ("to_ne_bytes", "byte arrays (`[u8; 4]`)"),
            ("from_be_bytes", "byte arrays (`[u8; 4]`)"),
            ("from_le_bytes", "byte arrays (`[u8; 4]`)"),
            ("from_ne_bytes", "byte arrays (`[u8; 4]`)"),
            ("abs_sub", "deprecated in std"),
        ],
    ),
    (
        "i32",
        &[
            "count_ones",
            "count_zeros",
            "leading_zeros",
            "trailing_zeros",
            "leading_ones",
            "trailing_ones",
            "cast_unsigned",
            "rotate_left",
            "rotate_right",
            "swap_bytes",
            "reverse_bits",
            "to_be",
            "to_le",
            "from_be",
            "from_le",
            "saturating_add",
            "saturating_add_unsigned",
            "saturating_sub",
            "saturating_sub_unsigned",
            "saturating_neg",
            "saturating_abs",
            "saturating_mul",
            "saturating_div",
            "saturating_pow",
            "wrapping_add",
            "wrapping_add_unsigned",
            "wrapping_sub",
            "wrapping_sub_unsigned",
            "wrapping_mul",
            "wrapping_div",
            "wrapping_div_euclid",
            "wrapping_rem",
            "wrapping_rem_euclid",
            "wrapping_neg",
            "wrapping_shl",
            "wrapping_shr",
            "wrapping_abs",
            "unsigned_abs",
            "wrapping_pow",
            "overflowing_add",
            "overflowing_sub",
            "overflowing_mul",
            "overflowing_neg",
            "overflowing_shl",
            "overflowing_shr",
            "overflowing_abs",
            "overflowing_pow",
            "overflowing_add_unsigned",
            "overflowing_sub_unsigned",
            "overflowing_div",
            "overflowing_div_euclid",
            "overflowing_rem",
            "overflowing_rem_euclid",
            "pow",
            "isqrt",
            "div_euclid",
            "rem_euclid",
            "abs",
            "abs_diff",
            "signum",
            "is_positive",
            "is_negative",
            "midpoint",
            "ilog",
            "ilog2",
            "ilog10",
            "unbounded_shl",
            "unbounded_shr",
            "min",
            "max",
            "clamp",
        ],
        &[
            ("checked_*", "returns `Option`"),
            ("unchecked_*", "unsafe"),
            ("to_be_bytes, to_le_bytes, to_ne_bytes, from_*_bytes", "byte arrays (`[u8; 4]`)"),
            ("from_str_radix", "strings"),
        ],
    ),
    (
        "u32",
        &[
            "count_ones",
            "count_zeros",
            "leading_zeros",
            "trailing_zeros",
            "leading_ones",
            "trailing_ones",
            "cast_signed",
            "rotate_left",
            "rotate_right",
            "swap_bytes",
            "reverse_bits",
            "to_be",
            "to_le",
            "from_be",
            "from_le",
            "saturating_add",
            "saturating_add_signed",
            "saturating_sub",
            "saturating_mul",
            "saturating_div",
            "saturating_pow",
            "wrapping_add",
            "wrapping_add_signed",
            "wrapping_sub",
            "wrapping_mul",
            "wrapping_div",
            "wrapping_div_euclid",
            "wrapping_rem",
            "wrapping_rem_euclid",
            "wrapping_neg",
            "wrapping_shl",
            "wrapping_shr",
            "wrapping_pow",
            "overflowing_add",
            "overflowing_add_signed",
            "overflowing_sub",
            "overflowing_mul",
            "overflowing_neg",
            "overflowing_shl",
            "overflowing_shr",
            "overflowing_pow",
            "overflowing_div",
            "overflowing_div_euclid",
            "overflowing_rem",
            "overflowing_rem_euclid",
            "pow",
            "isqrt",
            "div_euclid",
            "rem_euclid",
            "div_ceil",
            "next_multiple_of",
            "is_multiple_of",
            "is_power_of_two",
            "next_power_of_two",
            "abs_diff",
            "midpoint",
            "ilog",
            "ilog2",
            "ilog10",
            "unbounded_shl",
            "unbounded_shr",
            "min",
            "max",
            "clamp",
        ],
        &[
            ("checked_*", "returns `Option`"),
            ("unchecked_*", "unsafe"),
            ("to_be_bytes, to_le_bytes, to_ne_bytes, from_*_bytes", "byte arrays (`[u8; 4]`)"),
            ("from_str_radix", "strings"),
        ],
    ),
    ("bool", &[], &[("then_some", "returns `Option`"), ("then", "takes a closure")]),
];

/// `fn(A, ..) -> R` of a supported std function, in Rust.
fn rust_fn_type(params: &[Ty], ret: &Ty) -> String {
    let ps: Vec<String> = params.iter().map(Ty::to_string).collect();
    match ret {
        Ty::Unit => format!("fn({})", ps.join(", ")),
        r => format!("fn({}) -> {r}", ps.join(", ")),
    }
}

#[test]
fn supported_std_scalar_functions_have_std_signatures_and_the_table_is_current() {
    use rt_compiler::lower::builtins::{assoc_fn, method_sig};
    let mut doc = String::from(
        "# std's scalar methods in ray programs\n\n\
         Generated by `tests/tests/glam_coverage.rs` from the compiler's tables and a list of std's stable \
         inherent functions of `f32`, `i32`, `u32` and `bool` (`RT_BLESS=1 cargo test -p rt-tests --test \
         glam_coverage` rewrites it). Each supported function's signature is checked by rustc \
         (`tests/src/std_signatures.rs`, generated by the same test). Where std panics (an overflowing \
         `pow` in a debug build, a zero divisor, the logarithm of 0), programs get the GPU's meaning on \
         both backends: see `rt_std::arith`.\n\n",
    );
    let mut checks = String::from(
        "//! Generated by `tests/tests/glam_coverage.rs` (`RT_BLESS=1` rewrites it): every std function of the\n\
         //! scalars that ray programs may call, with the signature the compiler's table gives it. rustc\n\
         //! compiles this file with the tests, so a signature that differs from std's fails the build.\n\n\
         pub fn signatures() {\n",
    );
    let (mut yes_all, mut all) = (0, 0);
    for (owner, names, left_out) in STD {
        let ty = rt_compiler::types::builtin_type(owner).expect("a scalar type");
        let mut yes = Vec::new();
        let mut no: Vec<String> = Vec::new();
        for name in names.iter() {
            let found = method_sig(&ty, name).map(|s| {
                let mut params = vec![ty.clone()];
                params.extend(s.params);
                (params, s.ret)
            });
            let found = found.or_else(|| assoc_fn(&ty, name).map(|s| (s.params, s.ret)));
            match found {
                Some((params, ret)) => {
                    checks.push_str(&format!("    let _: {} = {owner}::{name};\n", rust_fn_type(&params, &ret)));
                    yes.push(format!("`{name}`"));
                }
                None => no.push(format!("`{name}` (not written out yet)")),
            }
        }
        no.extend(left_out.iter().map(|(n, why)| format!("`{n}` ({why})")));
        yes_all += yes.len();
        all += yes.len() + no.len();
        doc.push_str(&format!(
            "## {owner}: {} of {}\n\nSupported: {}\n\nLeft out: {}\n\n",
            yes.len(),
            yes.len() + no.len(),
            if yes.is_empty() { "none".to_string() } else { yes.join(", ") },
            if no.is_empty() { "none".to_string() } else { no.join(", ") }
        ));
    }
    checks.push_str("}\n");
    let doc =
        doc.replacen("\n\n## ", &format!("\n\n**{yes_all} of {all} supported** (a `*` entry counts once).\n\n## "), 1);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = [(root.join("../docs/std_methods.md"), doc), (root.join("src/std_signatures.rs"), checks)];
    for (path, text) in &files {
        if std::env::var_os("RT_BLESS").is_some() {
            std::fs::write(path, text).unwrap();
        }
        let current = std::fs::read_to_string(path).unwrap_or_default();
        assert!(&current == text, "{} is out of date (RT_BLESS=1 to rewrite it)", path.display());
    }
}
