//! glam methods WGSL has no builtin for, as the compiler writes them out:
//! matrix inverses, projections, `any_orthonormal_vector`, Euclidean
//! division of floats, `log10`, `copysign`, integer rotations and byte
//! swaps.

use super::*;

/// Well-conditioned matrices: the identity plus a small random part.
fn near_identity4(n: usize, seed: u32) -> Vec<Mat4> {
    mat4s(n, seed).into_iter().map(|m| Mat4::IDENTITY + m * 0.1).collect()
}

fn near_identity3(n: usize, seed: u32) -> Vec<Mat3> {
    mat3s(n, seed).into_iter().map(|m| Mat3::IDENTITY + m * 0.1).collect()
}

differential! {
    /// The methods of `glam_more.rs`, on both backends.
    fn glam_written_out {
        /// `Mat4::inverse`, `Mat3::inverse`, `Mat2::inverse` (glam's cofactor
        /// formulas; the products and sums round differently on the GPU).
        mat4_inverse(m: Mat4) -> [Mat4; 1] over one(&near_identity4(48, 11)), tol ulp_or_abs(64, 1e-5) => {
            [m.inverse()]
        }
        mat3_inverse(m: Mat3) -> [Mat3; 1] over one(&near_identity3(48, 12)), tol ulp_or_abs(64, 1e-5) => {
            [m.inverse()]
        }
        mat2_inverse(a: Vec4) -> [Vec4; 1] over one(&vec4s(48, 0.2, 13)), tol ulp_or_abs(16, 1e-5) => {
            let m = Mat2::from_cols(vec2(1.0 + a.x, a.y), vec2(a.z, 1.0 + a.w)).inverse();
            [vec4(m.x_axis.x, m.x_axis.y, m.y_axis.x, m.y_axis.y)]
        }
        /// Projections and rejections; an orthonormal vector to a unit one.
        projections(a: Vec3, b: Vec3) -> [Vec3; 5] over pairs(&vec3s(12, 2.0, 21), &vec3s_nonzero(8, 22)), tol ulp_or_abs(16, 1e-5) => {
            let n = b.normalize();
            [a.project_onto(b), a.reject_from(b), a.project_onto_normalized(n), a.reject_from_normalized(n), n.any_orthonormal_vector()]
        }
        /// `rem_euclid`/`div_euclid` of floats (exact), `copysign` (exact),
        /// `log10` (WGSL's `log2` accuracy and one rounding).
        float_methods(a: f32, b: f32) -> [f32; 4] over pairs(&spread(24, -7.5, 7.5), &[-2.5, -1.0, 0.75, 3.0]), tol ulp_or_abs(4, 1e-6) => {
            [a.rem_euclid(b), a.div_euclid(b), a.copysign(b), (a.abs() + 0.5).log10()]
        }
        /// Vector methods: component replacement, midpoints, `step`,
        /// `smoothstep`, `saturate`, `copysign`, length clamps, checks.
        vector_methods(a: Vec3, b: Vec3) -> [Vec3; 9] over pairs(&vec3s_nonzero(10, 31), &vec3s_nonzero(6, 32)), tol ulp_or_abs(16, 1e-5) => {
            let flags = vec3(a.is_normalized() as u32 as f32, a.normalize().is_normalized() as u32 as f32, a.abs_diff_eq(b, 1.5) as u32 as f32);
            [
                a.with_y(b.z), a.dot_into_vec(b), a.midpoint(b), a.step(b), a.smoothstep(-b.abs() - 0.5, b.abs() + 0.5),
                (a * 0.5).saturate(), a.copysign(b), a.clamp_length(0.5, 1.5) + a.clamp_length_max(1.0) + a.clamp_length_min(2.0), flags,
            ]
        }
        /// `Vec2`'s own: `perp`, `perp_dot`, `rotate`, `to_angle`; an
        /// integer vector's `with_x`.
        vec2_methods(a: Vec3, b: Vec3) -> [Vec3; 3] over pairs(&vec3s_nonzero(10, 33), &vec3s_nonzero(6, 34)), tol ulp_or_abs(16, 1e-5) => {
            let (p, q) = (a.truncate(), b.truncate());
            let i = ivec3(1, 2, 3).with_x(p.x as i32);
            [p.perp().extend(p.perp_dot(q)), p.rotate(q).extend(p.to_angle()), i.as_vec3()]
        }
        /// Matrix methods: rows, the diagonal, sums, scalings, `abs`,
        /// transposed products, 2D and projective transforms.
        matrix_methods(m: Mat4) -> [Vec4; 8] over one(&near_identity4(32, 35)), tol ulp_or_abs(16, 1e-5) => {
            let m3 = Mat3::from_cols(m.x_axis.truncate(), m.y_axis.truncate(), m.z_axis.truncate());
            let sum = m3.add_mat3(&m3).sub_mat3(&Mat3::IDENTITY).mul_scalar(0.5).div_scalar(4.0);
            let m2 = Mat2::from_cols(m3.x_axis.truncate(), m3.y_axis.truncate());
            [
                m.row(1), m.diagonal(), m.abs().col(2), m.transpose_mul_vec4(vec4(1.0, -2.0, 0.5, 1.0)),
                m.project_point3(vec3(0.5, -1.0, 2.0)).extend(1.0), sum.row(0).extend(sum.diagonal().z),
                m3.transform_point2(vec2(1.0, 2.0)).extend(0.0).extend(m3.transform_vector2(vec2(-1.0, 0.5)).y),
                m2.mul_mat2(&m2).mul_vec2(vec2(1.0, -1.0)).extend(0.0).extend(0.0),
            ]
        }
        /// Rotations by any amount (modulo 32, as Rust's), byte swaps.
        int_bits(a: u32, k: u32) -> [u32; 5] over pairs(&u64_grid(), &[0, 1, 7, 31, 32, 45]) => {
            let s = a as i32;
            [a.rotate_left(k), a.rotate_right(k), s.rotate_left(k) as u32, a.swap_bytes(), s.swap_bytes() as u32]
        }
    }
}
