//! The glam methods of `glam_angles.rs`, `glam_ints.rs` and part of
//! `glam_more.rs`: angles and rotations, normalizing with a fallback, tuple
//! results, Euclidean division of vectors, positions and sign masks,
//! integer-vector geometry, saturating arithmetic and matrix extras, on
//! both backends.

use super::*;

differential! {
    /// Float vectors.
    fn glam_added_float_vectors {
        /// `reflect`/`refract` of `Vec2`/`Vec4` (WGSL's builtins),
        /// `lerp_monotonic`, `normalize_or` (a zero vector gets the
        /// fallback), `to_homogeneous`, `project`.
        vec_extras(a: Vec3, b: Vec3) -> [Vec4; 6] over pairs(&vec3s_nonzero(8, 41), &vec3s(6, 2.0, 42)), tol ulp_or_abs(16, 1e-5) => {
            let n2 = a.truncate().normalize();
            let n4 = a.extend(0.5).normalize();
            let i2 = b.truncate().normalize_or(Vec2::Y);
            [
                i2.reflect(n2).extend(0.0).extend(0.0),
                i2.refract(n2, 0.7).extend(i2.refract(n2, 1.6).x).extend(0.0),
                b.extend(1.0).normalize_or(Vec4::W).reflect(n4),
                b.extend(-1.0).normalize_or(Vec4::X).refract(n4, 0.9),
                a.lerp_monotonic(b, 0.25).to_homogeneous(),
                (b * 0.0).normalize_or(Vec3::Z).extend(b.extend(2.0).project().x),
            ]
        }
        /// Tuple results: `sin_cos` (WGSL's `sin`/`cos` accuracy on
        /// `[-pi, pi]`), `normalize_and_length` (and its zero case).
        tuple_results(a: Vec3, s: f32) -> [Vec4; 4] over pairs(&vec3s(10, 3.0, 43), &[0.0, 1.0]), tol ulp_or_abs(16, 2e-6) => {
            let (sn, cs) = a.sin_cos();
            let (n, len) = (a * s).normalize_and_length();
            let (n2, len2) = (a.truncate() * s).normalize_and_length();
            let (s4, c4) = a.extend(-0.5).sin_cos();
            [sn.extend(cs.x), n.extend(len), n2.extend(len2).extend(0.0), s4 + c4]
        }
        /// `rem_euclid`/`div_euclid` per component (exact),
        /// `min_position`/`max_position`, `is_negative_bitmask`,
        /// `is_finite`/`is_nan` (of finite values).
        positions(a: Vec3, b: Vec3) -> [Vec4; 4] over pairs(&vec3s(10, 6.0, 44), &vec3s_nonzero(6, 45)), tol ulp_or_abs(0, 1e-6) => {
            let p = a.truncate();
            [
                a.rem_euclid(b).extend(a.extend(1.0).div_euclid(b.extend(-2.0)).w),
                a.div_euclid(b).extend(p.rem_euclid(b.truncate()).y),
                vec4(a.min_position() as f32, a.max_position() as f32, p.min_position() as f32, a.extend(-b.x).max_position() as f32),
                vec4(a.is_negative_bitmask() as f32, a.extend(b.y).is_negative_bitmask() as f32, (a.is_finite()) as u32 as f32, (b.extend(1.0).is_nan()) as u32 as f32),
            ]
        }
    }
}

differential! {
    /// Angles and rotations.
    fn glam_added_angles {
        /// `Vec2::angle_to`, `rotate_angle`, `rotate_towards` (glam's
        /// `acos_approx`), `move_towards`.
        angles_2d(a: Vec3, b: Vec3) -> [Vec4; 4] over pairs(&vec3s_nonzero(10, 51), &vec3s_nonzero(6, 52)), tol ulp_or_abs(64, 1e-5) => {
            let (p, q) = (a.truncate(), b.truncate());
            [
                vec4(p.angle_to(q), q.angle_to(p), p.angle_to(p * 2.0), 0.0),
                p.rotate_angle(b.z).extend(0.0).extend(0.0),
                p.rotate_towards(q, 0.25).extend(p.rotate_towards(q, -0.5).x).extend(p.rotate_towards(q, 10.0).y),
                p.move_towards(q, 0.5).extend(a.move_towards(b, 100.0).x).extend(a.extend(1.0).move_towards(b.extend(0.0), 0.1).w),
            ]
        }
        /// `Vec3::angle_between`, `angle_to`, the axis rotations,
        /// `rotate_axis`, `rotate_towards`, `any_orthogonal_vector`,
        /// `any_orthonormal_pair`.
        angles_3d(a: Vec3, b: Vec3) -> [Vec3; 8] over pairs(&vec3s_nonzero(10, 53), &vec3s_nonzero(6, 54)), tol ulp_or_abs(64, 2e-5) => {
            let axis = b.normalize();
            let (u, v) = axis.any_orthonormal_pair();
            [
                vec3(a.angle_between(b), a.angle_to(b, Vec3::Z), a.angle_between(a)),
                a.rotate_x(b.x),
                a.rotate_y(b.y),
                a.rotate_z(b.z),
                a.rotate_axis(axis, 0.7),
                a.rotate_towards(b, 0.3) + a.rotate_towards(a * 3.0, 0.1),
                a.any_orthogonal_vector() + a.yxz().any_orthogonal_vector(),
                u + v * 2.0,
            ]
        }
        /// `Vec3::slerp`: along the arc, and for (anti)parallel vectors.
        slerp(a: Vec3, b: Vec3) -> [Vec3; 4] over pairs(&vec3s_nonzero(10, 55), &vec3s_nonzero(6, 56)), tol ulp_or_abs(64, 5e-5) => {
            [a.slerp(b, 0.3), a.slerp(b, 1.0), a.slerp(a * 2.0, 0.5), a.slerp(-a, 0.25)]
        }
    }
}

/// `IVec3`s and `UVec3`s small enough that squared lengths do not
/// overflow (Rust's would panic).
fn small_ivec3s() -> Vec<IVec3> {
    ivec3s(12, 1000, 61)
}

differential! {
    /// Integer vectors and saturating arithmetic.
    fn glam_added_integers {
        /// Squared lengths and distances, `cross`, Manhattan and Chebyshev
        /// distances, `IVec2`'s `perp`/`perp_dot`/`rotate`, positions and
        /// sign masks.
        int_vectors(a: IVec3, b: IVec3) -> [IVec4; 5] over pairs(&small_ivec3s(), &ivec3s(5, 1000, 62)) => {
            let (p, q) = (a.truncate(), b.truncate());
            let (ua, ub) = (a.abs().as_uvec3(), b.abs().as_uvec3());
            [
                ivec4(a.length_squared(), a.distance_squared(b), p.length_squared(), a.extend(3).distance_squared(b.extend(-4))),
                a.cross(b).extend(0),
                ivec4(a.manhattan_distance(b) as i32, a.chebyshev_distance(b) as i32, ua.manhattan_distance(ub) as i32, ua.extend(9).chebyshev_distance(ub.extend(1)) as i32),
                p.perp().extend(p.perp_dot(q)).extend(0) + p.rotate(q).extend(0).extend(0),
                ivec4(a.min_position() as i32, a.max_position() as i32, ua.min_position() as i32, a.is_negative_bitmask() as i32),
            ]
        }
        /// `saturating_add`/`_sub`/`_mul` of `i32` and `u32`, at the edges.
        saturating_i32(a: i32, b: i32) -> [i32; 3] over pairs(&I32_EDGES, &I32_EDGES) => {
            [a.saturating_add(b), a.saturating_sub(b), a.saturating_mul(b)]
        }
        saturating_u32(a: u32, b: u32) -> [u32; 3] over pairs(&U32_EDGES, &U32_EDGES) => {
            [a.saturating_add(b), a.saturating_sub(b), a.saturating_mul(b)]
        }
        /// Mixed signs: `i32` with `u32` and back, wrapping and saturating,
        /// at the edges, on scalars and vectors.
        mixed_signs(a: i32, b: u32) -> [i32; 8] over pairs(&I32_EDGES, &U32_EDGES) => {
            let (u, s) = (b, a);
            let v = ivec2(a, a.wrapping_add(7)).saturating_add_unsigned(uvec2(b, 3));
            let w = uvec2(b, 1).saturating_add_signed(ivec2(a, -2));
            [
                a.wrapping_add_unsigned(b), a.wrapping_sub_unsigned(b), a.saturating_add_unsigned(b), a.saturating_sub_unsigned(b),
                u.wrapping_add_signed(s) as i32, u.saturating_add_signed(s) as i32, v.x + v.y.wrapping_sub(v.y),
                (w.x ^ w.y) as i32 ^ ivec2(a, 0).wrapping_sub_unsigned(uvec2(b, b)).x,
            ]
        }
        /// Per component on vectors.
        saturating_vectors(a: i32, b: i32) -> [IVec2; 3] over pairs(&I32_EDGES, &I32_EDGES) => {
            let (v, w) = (ivec2(a, b), ivec2(b, a.wrapping_add(1)));
            [v.saturating_add(w), v.saturating_sub(w), v.saturating_mul(w)]
        }
    }
}

differential! {
    /// Matrices.
    fn glam_added_matrices {
        /// `inverse_or_zero`: the inverse of invertible matrices, zero for
        /// singular ones (a zero column: a determinant exactly 0 on both
        /// sides, where a nearly singular one would round apart).
        inverse_or_zero(m: Mat4) -> [Mat4; 2] over one(&mat4s(16, 72)), tol ulp_or_abs(64, 1e-4) => {
            let near = Mat4::IDENTITY + m * 0.1;
            let singular = Mat4::from_cols(m.x_axis, Vec4::ZERO, m.z_axis, m.w_axis);
            let m3 = Mat3::from_cols(m.x_axis.truncate(), m.y_axis.truncate(), Vec3::ZERO).inverse_or_zero();
            let m2 = Mat2::from_cols(m.x_axis.truncate().truncate(), m.y_axis.truncate().truncate() * 0.0).inverse_or_zero();
            let small = Mat4::from_cols(m3.x_axis.extend(0.0), m3.y_axis.extend(0.0), m3.z_axis.extend(0.0), m2.x_axis.extend(0.0).extend(1.0));
            [near.inverse_or_zero(), singular.inverse_or_zero() + small]
        }
        /// `mul_diagonal_scale`, `recip`, `abs_diff_eq`, `is_finite`,
        /// `is_nan` (`mul_transpose_vecN`, deprecated in glam, lowers as
        /// `transpose_mul_vecN`, tested in `glam_more.rs`).
        matrix_extras(m: Mat4) -> [Vec4; 6] over one(&mat4s(24, 71)), tol ulp_or_abs(4, 1e-6) => {
            let m3 = Mat3::from_cols(m.x_axis.truncate(), m.y_axis.truncate(), m.z_axis.truncate());
            let m2 = Mat2::from_cols(m3.x_axis.truncate(), m3.y_axis.truncate());
            let r = (m + Mat4::from_diagonal(Vec4::splat(3.0))).recip();
            [
                m.mul_diagonal_scale(vec4(1.0, -2.0, 0.5, 1.0)).row(2),
                m3.mul_diagonal_scale(vec3(0.5, 1.0, -1.0)).row(0).extend(m2.mul_diagonal_scale(vec2(2.0, 1.0)).row(1).y),
                m.mul_diagonal_scale(vec4(2.0, -1.0, 0.5, 0.0)).col(1),
                r.col(0) + r.col(3),
                vec4((m.abs_diff_eq(m * 1.0001, 1e-3)) as u32 as f32, (m3.abs_diff_eq(Mat3::IDENTITY, 0.5)) as u32 as f32, (m.is_finite()) as u32 as f32, (m2.is_nan()) as u32 as f32),
                m3.mul_diagonal_scale(vec3(1.0, 2.0, 3.0)).recip().col(2).extend((m3.is_finite()) as u32 as f32),
            ]
        }
    }
}

/// `set_row` through a `&mut` helper parameter.
#[rt_function]
pub fn put_row(m: &mut Mat3, i: u32, v: Vec3) {
    m.set_row(i as usize, v);
}

/// `col_mut` through a `&mut` helper parameter.
#[rt_function]
pub fn put_col(m: &mut Mat3, i: u32, x: f32) {
    m.col_mut(i as usize).z -= x;
}

differential! {
    /// glam's in-place methods: `Mat2/3/4::set_row` and `col_mut` (on a
    /// local and through a `&mut` parameter), `BVecN::set` and
    /// `BVecN::test`.
    /// (`tests/integer_semantics.rs` has their indices past the end.)
    fn glam_in_place {
        set_rows(a: Vec4, i: u32) -> [Vec4; 9] over pairs(&vec4s(4, 2.0, 71), &[0, 1, 2]) => {
            let mut m2 = Mat2::IDENTITY;
            m2.set_row(i as usize % 2, a.truncate().truncate());
            let mut m3 = Mat3::from_diagonal(Vec3::splat(2.0));
            m3.set_row(i as usize, a.truncate());
            let mut m4 = Mat4::IDENTITY;
            m4.set_row(i as usize + 1, a);
            let mut p = Mat3::ZERO;
            put_row(&mut p, 2 - i, a.truncate() * 2.0);
            *m4.col_mut(3 - i as usize) += a * 0.5;
            m3.col_mut(i as usize).y = a.w;
            put_col(&mut p, i, a.x);
            [
                m2.x_axis.extend(m2.y_axis.x).extend(m2.y_axis.y),
                m3.x_axis.extend(0.0),
                m3.y_axis.extend(m3.z_axis.x),
                m3.z_axis.extend(0.0),
                m4.x_axis,
                m4.y_axis,
                m4.z_axis + m4.w_axis,
                p.x_axis.extend(p.y_axis.x),
                p.y_axis.extend(p.z_axis.z),
            ]
        }
        mask_set_test(a: u32, i: u32) -> [u32; 3] over pairs(&U16, &[0, 1, 2]) => {
            let mut m4 = bvec4(a & 1 != 0, a & 2 != 0, a & 4 != 0, a & 8 != 0);
            m4.set(i as usize + 1, a & 16 == 0);
            let mut m3 = BVec3::splat(a & 1 != 0);
            m3.set(i as usize, a & 2 != 0);
            let mut m2 = BVec2::new(a & 4 != 0, false);
            m2.set(i as usize % 2, true);
            let mut f = Vec4::splat(a as f32).cmpgt(Vec4::splat(7.0));
            f.set(i as usize, false);
            [
                m4.bitmask() | (m3.bitmask() << 4) | (m2.bitmask() << 8) | (f.bitmask() << 12),
                m4.test(i as usize) as u32 | ((m3.test(i as usize) as u32) << 1) | ((m2.test(1) as u32) << 2)
                    | ((f.test(3) as u32) << 3),
                m4.test(3) as u32 | ((m3.test(2 - i as usize) as u32) << 1),
            ]
        }
    }
}

differential! {
    /// glam's associated functions (`builtins/glam_assoc.rs`).
    fn glam_assoc {
        /// Without trigonometry: from arrays, rows, other matrices,
        /// translations and scales (exact but for the products' rounding).
        exact(a: Vec4, b: Vec4) -> [Vec4; 10] over pairs(&vec4s(6, 2.0, 81), &vec4s(4, 2.0, 82)), tol CHAINED => {
            let arr = a.to_array();
            let m2 = Mat2::from_cols_array(&arr) + Mat2::from_rows_array(&[b.w, b.z, b.y, b.x]);
            let m2d = Mat2::from_cols_array_2d(&[[a.x, b.y], [a.z, b.w]]);
            let m3 = Mat3::from_rows(a.truncate(), b.truncate(), a.wxy()) + Mat3::from_cols_array(&[a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w, 1.0]);
            let m3b = Mat3::from_cols_array_2d(&[[a.x, a.y, a.z], [b.x, b.y, b.z], [a.w, b.w, 0.5]]) + Mat3::from_rows_array(&[b.x, b.y, b.z, b.w, a.x, a.y, a.z, a.w, 2.0]);
            let m4 = Mat4::from_rows(a, b, a.wzyx(), b.yxwz()) + Mat4::from_cols_array_2d(&[[a.x, a.y, a.z, a.w], [b.x, b.y, b.z, b.w], [1.0, 2.0, 3.0, 4.0], [b.w, a.w, b.z, a.z]]);
            let affine = Mat3::from_translation(a.xy()) * Mat3::from_scale(b.xy()) * Mat3::from_mat2(m2d);
            let big = Mat4::from_translation(a.truncate()) * Mat4::from_scale(b.truncate()) * Mat4::from_mat3(m3);
            let placed = Mat4::from_mat3_translation(m3b, b.truncate());
            let back = Mat3::from_mat4(m4) + Mat3::from_cols(a.truncate(), b.truncate(), Vec3::ONE);
            let small = Mat2::from_mat3(m3) + Mat2::from_rows(a.xy(), b.xy()) + Mat2::from_diagonal(a.zw());
            [
                m2.x_axis.extend(m2.y_axis.x).extend(m2.y_axis.y),
                m3.x_axis.extend(m3.y_axis.y),
                m3b.z_axis.extend(m3b.y_axis.x),
                m4.x_axis + m4.w_axis,
                m4.y_axis - m4.z_axis,
                affine.z_axis.extend(affine.x_axis.x),
                big.w_axis,
                big.y_axis + placed.w_axis,
                back.x_axis.extend(back.z_axis.y),
                small.x_axis.extend(small.y_axis.x).extend(small.y_axis.y),
            ]
        }
        /// With trigonometry (WGSL's `sin`/`cos`: 2^-11 absolute on
        /// `[-pi, pi]`, through products of up to three matrices).
        rotations(a: Vec4, t: f32) -> [Vec4; 8] over pairs(&vec4s(6, 1.0, 83), &[-3.0, -1.25, 0.0, 0.5, 2.75]), tol ulp_or_abs(16, 4e-3) => {
            let axis = a.truncate().normalize_or(Vec3::Y);
            let m3 = Mat3::from_axis_angle(axis, t);
            let m4 = Mat4::from_axis_angle(axis, t);
            let r3 = Mat3::from_rotation_x(t) * Mat3::from_rotation_y(t * 0.5) * Mat3::from_rotation_z(-t);
            let r4 = Mat4::from_rotation_x(t) * Mat4::from_rotation_y(0.25) * Mat4::from_rotation_z(t);
            let m2 = Mat2::from_angle(t) + Mat2::from_scale_angle(a.xy(), -t);
            let s = Mat3::from_scale_angle_translation(a.zw(), t, a.xy()) * Mat3::from_angle(t * 0.5);
            [
                m3.x_axis.extend(m3.y_axis.x),
                m3.z_axis.extend(m4.w_axis.w),
                m4.x_axis + m4.z_axis,
                r3.x_axis.extend(r3.y_axis.z),
                r4.y_axis + r4.w_axis,
                m2.x_axis.extend(m2.y_axis.x).extend(m2.y_axis.y),
                s.z_axis.extend(s.x_axis.x),
                Vec2::from_angle(t).extend(s.y_axis.y).extend(m3.z_axis.x),
            ]
        }
        /// `Mat3::from_mat4_minor` and `Mat2::from_mat3_minor` over every
        /// column and row left out.
        minors(a: Vec4, k: u32) -> [Vec4; 3] over pairs(&vec4s(4, 2.0, 85), &[0, 1, 2, 3]), tol EXACT => {
            let m4 = Mat4::from_cols(a, a.wzyx() + Vec4::ONE, a * 2.0, Vec4::new(1.0, 2.0, 3.0, 4.0));
            let m3 = Mat3::from_mat4_minor(m4, k as usize, 3 - k as usize);
            let m2 = Mat2::from_mat3_minor(m3, (k % 3) as usize, (2 - k % 3) as usize);
            [m3.x_axis.extend(m3.y_axis.x), m3.z_axis.extend(m3.y_axis.z), m2.x_axis.extend(m2.y_axis.x).extend(m2.y_axis.y)]
        }
        /// The vectors' and masks' `from_array`, `Vec3::from_homogeneous`.
        vectors(a: Vec4, k: i32) -> [Vec4; 3] over pairs(&vec4s(6, 2.0, 84), &I32_EDGES), tol CHAINED => {
            let v = Vec3::from_array([a.x, a.y, a.z]) + Vec3::from_homogeneous(a.with_w(a.w.abs() + 0.5));
            let i = IVec2::from_array([k, k / 3]);
            let u = UVec4::from_array([k as u32, 7, k as u32 >> 3, 1]);
            let m = BVec3::from_array([k > 0, a.x > a.y, k % 2 == 0]);
            [
                v.extend(Vec4::from_array(a.to_array()).w),
                vec4(i.x as f32, i.y as f32, (u.x >> 8) as f32, u.z as f32),
                Vec2::from_array([a.w, a.z]).extend(m.bitmask() as f32).extend(IVec3::from_array([1, k, 2]).y as f32),
            ]
        }
    }
}
