//! Matrices: `Mat3`/`Mat4` from columns, from a diagonal and as constants,
//! products with vectors, matrices and scalars, `transpose`, `determinant`,
//! columns by field and by `col`, and `transform_point3` and
//! `transform_vector3`: an object-space shading frame built by hand.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(closest_hit)]
pub fn matrices(prd: &mut Radiance, attr: &Normals, #[var] model: Mat4, #[var] tint: Mat3) {
    let n = attr.shading_normal.normalize();
    let up = if n.y.abs() < 0.999 { Vec3::Y } else { Vec3::X };
    let t = up.cross(n).normalize();
    let b = n.cross(t);
    let tbn = Mat3::from_cols(t, b, n);
    let world_to_tangent = tbn.transpose();
    let ray = current_ray();
    let local_dir = world_to_tangent * -ray.direction;
    let scale = Mat3::from_diagonal(vec3(2.0, 1.0, 0.5));
    let shaded = (tint * scale).mul_vec3(local_dir) + tint.mul_mat3(&Mat3::IDENTITY).col(2);
    let hit = model.transform_point3(ray.origin + t_hit() * ray.direction);
    let axis = model.transform_vector3(Vec3::Z) + model.w_axis.xyz() + model.x_axis.truncate();
    let m4 = model * Mat4::IDENTITY + Mat4::ZERO - model * 0.5;
    let clip = m4 * hit.extend(1.0) + m4.mul_vec4(Vec4::W) + 2.0 * (m4.mul_mat4(&model) * Vec4::X);
    let det = tbn.determinant() + tint.z_axis.z + tbn.y_axis.x;
    prd.result = (shaded + axis * det + clip.xyz() / clip.w) * (Mat3::ZERO + tbn).col(0).length();
}
