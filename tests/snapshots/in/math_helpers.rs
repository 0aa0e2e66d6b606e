//! rt-std's GLSL-style helpers on scalars and vectors: `reflect`,
//! `refract`, `faceforward`, `smoothstep`, `step`, `saturate` and `mix`
//! (with a scalar and with a per-component factor), as a rim-lit, banded
//! toon shader uses them.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(closest_hit)]
pub fn math_helpers(
    prd: &mut Radiance,
    attr: &Normals,
    #[var] base_color: Vec3,
    #[var] rim_color: Vec3,
    #[var] light_dir: Vec3,
    #[var] ior: f32,
) {
    let ray = current_ray();
    let n = faceforward(attr.shading_normal, ray.direction, attr.geometric_normal);
    let r = reflect(ray.direction, n);
    let tr = refract(ray.direction, n, 1.0 / ior);
    let n_dot_l = saturate(n.dot(light_dir));
    let band = step(0.5, n_dot_l) * 0.5 + step(0.9, n_dot_l) * 0.5;
    let rim = smoothstep(0.6, 1.0, 1.0 - saturate(n.dot(-ray.direction)));
    let spec = smoothstep(Vec3::splat(0.9), Vec3::ONE, r * light_dir);
    let edges = step(Vec3::splat(0.25), tr.abs()) + saturate(tr * 4.0);
    let lit = mix(base_color * 0.2, base_color, band);
    let toned = mix(lit, rim_color, Vec3::splat(rim)) + mix(0.0, 0.1, rim) * spec;
    prd.result = mix(toned, edges, vec3(0.0, 0.05, 0.1));
}
