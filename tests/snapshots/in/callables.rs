//! Callable programs: a callable's own module (its arguments by value, a
//! helper, a call of another signature), and a ray-generation program
//! calling through ids held in a variable, a buffer and a struct field
//! and an id made from a `u32` (each `.call` is the signature's dispatch
//! stub, `rt_call_<signature>`).
use rt_std::prelude::*;

/// Shades with the material's BRDF.
#[rt_struct]
pub struct Shader {
    pub brdf: Callable<fn(Vec3, Vec3, Vec3) -> Vec3>,
    pub tint: Vec3,
}

#[rt_function]
pub fn half_vector(l: Vec3, v: Vec3) -> Vec3 {
    (l + v).normalize()
}

/// A Blinn specular lobe whose exponent is another callable's answer.
#[rt_program(callable)]
pub fn blinn(n: Vec3, l: Vec3, v: Vec3, exponent: Callable<fn(f32) -> f32>) -> Vec3 {
    let e = exponent.call(n.dot(l));
    Vec3::splat(n.dot(half_vector(l, v)).max(0.0).powf(e))
}

#[rt_program(ray_generation)]
pub fn call_through_ids(
    #[var] shader: Shader,
    #[var] brdfs: Buffer<Callable<fn(Vec3, Vec3, Vec3) -> Vec3>>,
    #[var] exponent: Callable<fn(f32) -> f32>,
    #[var] mut out: RwBuffer<Vec3>,
) {
    let i = launch_index().x;
    let n = vec3(0.0, 0.0, 1.0);
    let l = vec3(0.6, 0.0, 0.8);
    let v = vec3(-0.6, 0.0, 0.8);
    let by_buffer = brdfs[i % brdfs.len()].call(n, l, v);
    let by_struct = shader.brdf.call(n, l, v) * shader.tint;
    let picked = Callable::<fn(f32) -> f32>::from_id(i + 1).call(0.25);
    out[i] = by_buffer + by_struct + Vec3::splat(exponent.call(0.5) + picked);
}

/// A tint whose strength and ramp are the callable program's variables
/// (its own scope, then the context's): in the WGSL they come first, then
/// its argument.
#[rt_program(callable)]
pub fn tinted(c: Vec3, #[var] strength: f32, #[var] ramp: Buffer<f32>) -> Vec3 {
    c * strength * ramp[0]
}
