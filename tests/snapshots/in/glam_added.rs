//! glam methods written out in `glam_angles.rs`, `glam_ints.rs` and the
//! later part of `glam_more.rs`, some on constant operands (which must not
//! become WGSL constant expressions that overflow or divide by zero).
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn glam_added(#[var] a: Vec3, #[var] b: Vec3, #[var] k: i32, #[var] mut out: RwBuffer<Vec4>) {
    let i = launch_index().x;
    let (u, v) = b.normalize().any_orthonormal_pair();
    let (s, c) = a.sin_cos();
    let (n, len) = a.normalize_and_length();
    let turned = a.rotate_axis(Vec3::Z, 0.5) + a.rotate_towards(b, 0.25) + a.rotate_x(0.1);
    let flat = a.truncate().angle_to(b.truncate()) + Vec3::X.angle_between(Vec3::Y) + a.angle_to(b, Vec3::Z);
    let moved = a.move_towards(b, 0.5) + a.normalize_or(Vec3::Y) + a.any_orthogonal_vector();
    let e = a.rem_euclid(b) + a.div_euclid(Vec3::splat(2.0));
    let ints = ivec3(k, 2, 3);
    let sat = k.saturating_mul(k) + 5i32.saturating_mul(0) + ints.saturating_add(IVec3::MAX).x;
    let geo = ints.cross(IVec3::ONE.cross(IVec3::X)).length_squared() + ints.manhattan_distance(IVec3::ZERO) as i32;
    let pos = (a.min_position() + ints.max_position()) as u32 + a.is_negative_bitmask() + 7u32.saturating_sub(9);
    out[i] = (u + v + s + c + n * len + turned + moved + e).extend(flat + (sat + geo) as f32 + pos as f32);
}
