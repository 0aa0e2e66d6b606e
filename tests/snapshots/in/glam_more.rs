//! glam methods WGSL has no builtin for, written out by the compiler:
//! `Mat4::inverse` (and `Mat3`'s), projections, `any_orthonormal_vector`,
//! `clamp_length`, `rem_euclid`, `log10`, `rotate_left`, matrix rows.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn glam_more(#[var] to_world: Mat4, #[var] normals: Buffer<Vec3>, #[var] mut out: RwBuffer<Vec4>) {
    let i = launch_index().x;
    let n = normals[i].normalize();
    let to_object = to_world.inverse();
    let tangent = n.any_orthonormal_vector();
    let d = Vec3::new(1.0, 2.0, 3.0).reject_from(n).clamp_length_max(1.0) + Vec3::X.project_onto(tangent);
    let p = to_object.transform_point3(d) + Mat3::from_cols(n, tangent, n.cross(tangent)).inverse().row(0);
    let phase = (p.x * 3.0).rem_euclid(1.0) + (p.y.abs() + 1.0).log10();
    out[i] = p.extend(phase + i.rotate_left(7) as f32);
}
