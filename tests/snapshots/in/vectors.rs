//! Float vector methods a shader writer reaches for, as glam spells them:
//! products, lengths and distances, per-component math, interpolation,
//! rounding, extension and truncation, swizzles, reductions, indexing and
//! component assignment, and vector/scalar arithmetic both ways round.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(miss)]
pub fn vectors(prd: &mut Radiance, #[var] a: Vec3, #[var] b: Vec3, #[var] t: f32) {
    let d = current_ray().direction;
    let n = a.cross(b).normalize();
    let cos = d.dot(n);
    let len = a.length() + b.length_squared() + a.length_recip();
    let dist = a.distance(b) + a.distance_squared(b);
    let safe = (a - b).normalize_or_zero();
    let per = a.abs().min(b).max(Vec3::splat(0.1)).clamp(Vec3::ZERO, Vec3::ONE);
    let blend = a.lerp(b, t);
    let curve = a.abs().powf(2.2) + b.abs().sqrt() + a.exp() + b.abs().ln() + a.exp2() + b.abs().log2();
    let waves = a.sin() * b.cos() + a.recip() + a.mul_add(b, Vec3::ONE);
    let rounded = a.floor() + a.ceil() + a.round() + a.trunc() + a.fract() + a.fract_gl() + a.signum();
    let mirrored = d.reflect(n) + d.refract(n, 1.0 / 1.5);
    let h = a.extend(1.0);
    let back = h.truncate() + vec4(1.0, 2.0, 3.0, 4.0).xyz();
    let uv = d.xy() + d.zx() + vec2(t, t).yx();
    let wide = d.xyzx() + d.zzzz() + Vec4::new(0.0, 1.0, 2.0, 3.0).wzyx();
    let reduced = a.element_sum() + a.element_product() + a.min_element() + b.max_element() + wide.max_element();
    let mut c = 2.0 * per + blend / 3.0 - curve * 0.5 + waves % 4.0 - -rounded;
    c.x = c[1] + c.y;
    c[2] = uv.x + uv[1];
    c += mirrored;
    c -= Vec3::X;
    c *= safe + back;
    c /= Vec3::splat(len + dist + cos + reduced);
    c *= 0.5;
    prd.result = c + Vec3::Y * h.w + Vec3::NEG_Z + Vec3::NEG_ONE + Vec3::Z * Vec4::W.w + Vec3::NEG_X + Vec3::NEG_Y;
}
