//! glam's associated functions: matrices from arrays, rows, angles, axes,
//! translations and scales (WGSL helpers after glam's formulas), vectors
//! and masks from arrays.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn glam_assoc(#[var] a: Vec4, #[var] t: f32, #[var] mut out: RwBuffer<f32>) {
    let m3 =
        Mat3::from_axis_angle(a.truncate(), t) * Mat3::from_rotation_y(t) * Mat3::from_rows(a.xyz(), a.yzw(), a.zwx());
    let m4 = Mat4::from_rotation_x(t) * Mat4::from_translation(a.truncate()) * Mat4::from_mat3(m3);
    let m2 = Mat2::from_scale_angle(a.xy(), t) + Mat2::from_cols_array(&a.to_array());
    let s = Mat3::from_scale_angle_translation(a.zw(), t, a.xy());
    let v = Vec3::from_homogeneous(a) + Vec3::from_array([t, t, 1.0]);
    let m = BVec2::from_array([t > 0.0, a.x > 0.0]);
    let minor = Mat2::from_mat3_minor(Mat3::from_mat4_minor(m4, 1, 2), 0, 1);
    out[0] = m4.w_axis.x + m2.y_axis.y + s.z_axis.x + v.y + m.bitmask() as f32 + Vec2::from_angle(t).x + minor.y_axis.x;
}
