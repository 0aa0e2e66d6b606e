//! The WGSL text the compiler and the runtime share: the records programs
//! and the megakernel exchange, the exception codes, and the stubs of the
//! runtime functions that programs are validated against at `cargo build`.

use crate::constants;
use crate::intrinsics::{AbiTy, WgslFn, wgsl_functions};

/// The records a lowered program and the runtime pass each other: the ray,
/// a bounding box, and the heap handles of buffers and samplers. Both the
/// compiler's stub module and the megakernel begin with this text.
pub const RECORDS: &str = "\
struct RtRay {
    origin: vec3<f32>,
    direction: vec3<f32>,
    ray_type: u32,
    tmin: f32,
    tmax: f32,
}
struct RtAabb {
    min: vec3<f32>,
    max: vec3<f32>,
}
struct RtBuffer {
    offset: u32,
    len: u32,
    width: u32,
    height: u32,
}
struct RtSampler {
    offset: u32,
    width: u32,
    height: u32,
    mode: u32,
}
struct RtSampler3d {
    offset: u32,
    width: u32,
    height: u32,
    depth: u32,
    mode: u32,
}
";

/// An f32 as WGSL text every conformant compiler accepts: the shortest
/// decimal that round-trips, with `f`; the extremes `±f32::MAX` as hex
/// floats (their shortest decimal, `3.4028235e38`, lies above `f32::MAX`,
/// and Tint rejects a literal it cannot represent); infinity and NaN as a
/// call of `FLOATS`' `rt_f32_from_bits`. WGSL has no literal for those,
/// and a constant expression that evaluates to one is a shader-creation
/// error (Tint: "value inf cannot be represented as 'f32'"; naga lets
/// `bitcast<f32>(0x7f800000u)` through): a call of a user function is never
/// a constant expression, so the bitcast happens at run time. The one
/// spelling of f32 values for the compiler and the runtime alike.
///
/// ```
/// use rt_abi::wgsl::f32_wgsl;
/// assert_eq!(f32_wgsl(0.5), "0.5f");
/// assert_eq!(f32_wgsl(f32::MIN), "-0x1.fffffep+127f");
/// assert_eq!(f32_wgsl(f32::INFINITY), "rt_f32_from_bits(0x7f800000u)");
/// ```
pub fn f32_wgsl(v: f32) -> String {
    if v.is_nan() {
        return format!("{F32_FROM_BITS}({F32_NAN_BITS:#010x}u)");
    }
    if v.is_infinite() {
        return format!("{F32_FROM_BITS}({:#010x}u)", v.to_bits());
    }
    if v.abs() == f32::MAX {
        return if v > 0.0 { "0x1.fffffep+127f".into() } else { "-0x1.fffffep+127f".into() };
    }
    format!("{v:?}f")
}

/// The function [`f32_wgsl`] spells infinity and NaN with: lowered code
/// that calls it is not a constant expression.
pub const F32_FROM_BITS: &str = "rt_f32_from_bits";

/// The bits lowered code gives every NaN (Rust's `f32::NAN`, quiet).
const F32_NAN_BITS: u32 = 0x7fc0_0000;

/// What [`f32_wgsl`] spells infinity and NaN with, and `RT_F32_MAX` (the
/// runtime's WGSL files read it, so that the extreme is spelled once): in
/// the compiler's stub module and in every megakernel.
pub fn floats() -> String {
    format!(
        "fn {F32_FROM_BITS}(bits: u32) -> f32 {{ return bitcast<f32>(bits); }}\nconst RT_F32_MAX: f32 = {};\n",
        f32_wgsl(f32::MAX)
    )
}

/// The heap binding every lowered program reads buffers through, and the
/// two word accessors all its reads and writes go through (`rt_hw`,
/// `rt_hw_set`): lowered code never indexes `rt_heap` itself, so the same
/// code runs over [`ATOMIC_HEAP`].
pub const HEAP: &str = "@group(0) @binding(0) var<storage, read_write> rt_heap: array<u32>;
fn rt_hw(w: u32) -> u32 { return rt_heap[w]; }
fn rt_hw_set(w: u32, v: u32) { rt_heap[w] = v; }
";

/// The heap of a module or megakernel where some program updates buffer
/// elements atomically ([`ATOMIC_PREFIX`]): the same binding, of atomic
/// words, read and written with relaxed atomic loads and stores.
pub const ATOMIC_HEAP: &str = "@group(0) @binding(0) var<storage, read_write> rt_heap: array<atomic<u32>>;
fn rt_hw(w: u32) -> u32 { return atomicLoad(&rt_heap[w]); }
fn rt_hw_set(w: u32, v: u32) { atomicStore(&rt_heap[w], v); }
";

/// The name prefix of the compiler's atomic buffer accessors
/// (`rt_atomic_add_u32`, ...): a program whose functions include one needs
/// [`ATOMIC_HEAP`], and so does every megakernel that links it.
pub const ATOMIC_PREFIX: &str = "rt_atomic";

/// Whether a module whose functions are named `names` needs
/// [`ATOMIC_HEAP`]: one of them is an atomic accessor. The compiler asks it
/// of a program's module, the runtime of a megakernel's linked functions.
pub fn needs_atomic_heap<'a>(mut names: impl Iterator<Item = &'a str>) -> bool {
    names.any(|n| n.starts_with(ATOMIC_PREFIX))
}

/// [`ATOMIC_HEAP`] or [`HEAP`].
pub fn heap(atomic: bool) -> &'static str {
    if atomic { ATOMIC_HEAP } else { HEAP }
}

/// The runtime's exception codes (`RT_EXC_*`) and the ray flags
/// (`RT_RAY_FLAG_*`) as WGSL constants.
pub fn constants() -> String {
    let mut s = u32_constants(&[
        ("RT_EXC_TRACE_DEPTH", constants::EXCEPTION_TRACE_DEPTH_EXCEEDED),
        ("RT_EXC_BUFFER_INDEX", constants::EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS),
        ("RT_EXC_INVALID_RAY", constants::EXCEPTION_INVALID_RAY),
        ("RT_EXC_PROGRAM_ID", constants::EXCEPTION_PROGRAM_ID_INVALID),
        ("RT_EXC_BUFFER_ID", constants::EXCEPTION_BUFFER_ID_INVALID),
        ("RT_EXC_TEXTURE_ID", constants::EXCEPTION_TEXTURE_ID_INVALID),
    ]);
    for (name, value) in constants::CONSTANTS.iter().filter(|(n, _)| n.starts_with("RAY_FLAG_")) {
        s.push_str(&u32_constants(&[(&format!("RT_{name}"), *value)]));
    }
    s
}

/// `fn rt_exc_bit(code: u32) -> u32`: [`constants::exception_kind_bit`] in
/// WGSL, one test per built-in exception code of [`constants::CONSTANTS`],
/// so that the megakernel's mask of enabled kinds cannot miss a kind the
/// contract adds.
pub fn exception_kind_bits() -> String {
    let mut s = String::from("fn rt_exc_bit(code: u32) -> u32 {\n");
    let user = constants::exception_kind_bit(constants::EXCEPTION_USER);
    for (_, code) in constants::CONSTANTS.iter().filter(|(n, _)| n.starts_with("EXCEPTION_")) {
        let bit = constants::exception_kind_bit(*code);
        if bit != user {
            s.push_str(&format!("    if code == {code}u {{ return {bit}u; }}\n"));
        }
    }
    s.push_str(&format!("    return {user}u;\n}}\n"));
    s
}

/// `const NAME: u32 = Vu;`, a line each.
pub(crate) fn u32_constants(pairs: &[(&str, u32)]) -> String {
    pairs.iter().map(|(n, v)| format!("const {n}: u32 = {v}u;\n")).collect()
}

/// A value of `ty` for a stub to return.
fn zero(ty: AbiTy) -> String {
    match ty {
        AbiTy::Unit => String::new(),
        AbiTy::Bool => "false".into(),
        AbiTy::U32 | AbiTy::TransformKind => "0u".into(),
        AbiTy::F32 => "0.0".into(),
        other => format!("{}()", other.wgsl()),
    }
}

/// `fn name(a: T, ...) -> R`: the signature line of `f`.
pub fn signature(f: &WgslFn) -> String {
    let params: Vec<String> = f.params.iter().map(|(n, t)| format!("{n}: {}", t.wgsl())).collect();
    match f.ret {
        AbiTy::Unit => format!("fn {}({})", f.name, params.join(", ")),
        ret => format!("fn {}({}) -> {}", f.name, params.join(", "), ret.wgsl()),
    }
}

/// The stub of `f`: its signature with a body that returns a zero value.
pub fn stub(f: &WgslFn) -> String {
    match f.ret {
        AbiTy::Unit => format!("{} {{}}", signature(f)),
        ret => format!("{} {{ return {}; }}", signature(f), zero(ret)),
    }
}

/// The fixed part of the compiler's stub prelude: the records, the heap and
/// a stub for every function of the contract.
/// The heap is [`heap`]`(atomic)`.
pub fn stub_prelude(atomic: bool) -> String {
    let mut s = String::from(RECORDS);
    s.push_str(heap(atomic));
    s.push_str(&floats());
    for f in wgsl_functions() {
        s.push_str(&stub(f));
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stubs_spell_their_signatures() {
        let f = crate::intrinsic("rt_transform_point").unwrap().wgsl.unwrap();
        assert_eq!(stub(&f), "fn rt_transform_point(kind: u32, p: vec3<f32>) -> vec3<f32> { return vec3<f32>(); }");
        let t = crate::intrinsic("rt_terminate_ray").unwrap().wgsl.unwrap();
        assert_eq!(stub(&t), "fn rt_terminate_ray() {}");
        assert!(stub_prelude(false).starts_with(RECORDS));
    }

    #[test]
    fn f32_text_round_trips_and_stays_finite() {
        for v in [0.0f32, -0.0, 1.0, 0.1, 1e-45, f32::MIN_POSITIVE, f32::EPSILON, 3.4028233e38, -1.5e30] {
            let s = f32_wgsl(v);
            let back: f32 = s.strip_suffix('f').unwrap().parse().unwrap();
            assert_eq!(back.to_bits(), v.to_bits(), "{s}");
            // No decimal above f32::MAX: every conformant compiler takes it.
            assert!(s.strip_suffix('f').unwrap().parse::<f64>().unwrap().abs() <= f32::MAX as f64, "{s}");
        }
        assert_eq!(f32_wgsl(f32::MAX), "0x1.fffffep+127f");
        assert_eq!(f32_wgsl(f32::NEG_INFINITY), "rt_f32_from_bits(0xff800000u)");
        assert_eq!(f32_wgsl(f32::NAN), "rt_f32_from_bits(0x7fc00000u)");
        assert!(floats().contains("const RT_F32_MAX: f32 = 0x1.fffffep+127f;"));
        assert!(stub_prelude(false).contains(&floats()));
    }

    #[test]
    fn exception_kind_bits_cover_every_built_in_code() {
        let text = exception_kind_bits();
        for (name, code) in constants::CONSTANTS.iter().filter(|(n, _)| n.starts_with("EXCEPTION_")) {
            let bit = constants::exception_kind_bit(*code);
            let line = format!("    if code == {code}u {{ return {bit}u; }}\n");
            // A code enabled with the programs' own (`EXCEPTION_PANIC`) is
            // the function's last line, not a test of its own.
            let user = constants::exception_kind_bit(constants::EXCEPTION_USER);
            assert_eq!(text.contains(&line), bit != user, "{name}: {text}");
        }
        assert!(text.contains("if code == 1007u { return 256u; }"), "{text}");
        assert!(text.ends_with("    return 32u;\n}\n"), "{text}");
    }
}
