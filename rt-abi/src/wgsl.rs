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
";

/// The heap binding every lowered program reads buffers through.
pub const HEAP: &str = "@group(0) @binding(0) var<storage, read_write> rt_heap: array<u32>;\n";

/// The runtime's exception codes (`RT_EXC_*`) and the ray flags
/// (`RT_RAY_FLAG_*`) as WGSL constants.
pub fn constants() -> String {
    let mut s = u32_constants(&[
        ("RT_EXC_TRACE_DEPTH", constants::EXCEPTION_TRACE_DEPTH_EXCEEDED),
        ("RT_EXC_BUFFER_INDEX", constants::EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS),
        ("RT_EXC_INVALID_RAY", constants::EXCEPTION_INVALID_RAY),
    ]);
    for (name, value) in constants::CONSTANTS.iter().filter(|(n, _)| n.starts_with("RAY_FLAG_")) {
        s.push_str(&u32_constants(&[(&format!("RT_{name}"), *value)]));
    }
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
pub fn stub_prelude() -> String {
    let mut s = String::from(RECORDS);
    s.push_str(HEAP);
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
        assert!(stub_prelude().starts_with(RECORDS));
    }
}
