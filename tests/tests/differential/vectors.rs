//! Float and integer vectors, matrices.

use super::*;

// ---------------------------------------------------------------------------
// Float vectors
// ---------------------------------------------------------------------------

differential! {
    /// glam's `Vec2`/`Vec3`/`Vec4` methods and operators.
    fn float_vectors {
        /// Component-wise `+ - *`, negation, and scalars on either side.
        vec3_arith(a: Vec3, b: Vec3) -> [Vec3; 7]
            over pairs(&vec3s(16, 100.0, 1), &vec3s(16, 100.0, 2)), tol CHAINED => {
            [a + b, a - b, a * b, -a, a * 2.5, 0.5 * b, a + 1.0 - b * -3.0]
        }
        /// Component-wise `/` and `%` (Rust's remainder per component), by
        /// vectors and by scalars (`/`: 2.5 ULP in WGSL).
        vec3_div_rem(a: Vec3, b: Vec3) -> [Vec3; 4]
            over pairs(&vec3s(16, 100.0, 3), &vec3s_nonzero(16, 4)), tol ulp(3) => {
            [a / b, a / 4.0, 2.0 / b, a % b + a % 3.0 - 7.5 % b]
        }
        /// Compound assignment by vectors and scalars, component access by
        /// field and by index, and component assignment.
        vec3_compound(a: Vec3, b: Vec3) -> [Vec3; 4]
            over pairs(&vec3s(16, 10.0, 5), &vec3s_nonzero(16, 6)), tol ulp(3) => {
            let mut c = a;
            c += b;
            c -= Vec3::X;
            c *= b;
            let s1 = c;
            c *= 0.5;
            c /= b;
            c /= 2.0;
            let s2 = c;
            c.x = c[1] + c.y;
            c[2] = a.x - b[0];
            let mut d = Vec4::ZERO;
            d.w = c.z;
            d[1] = 3.0;
            [s1, s2, c, d.xyz() + d.w]
        }
        /// `dot` and `cross`: WGSL inherits their accuracy from the products
        /// and sums (in any order, possibly fused), so with cancellation the
        /// bound is absolute (a few ULP of the largest term, here <= 100).
        dot_cross(a: Vec3, b: Vec3) -> [Vec3; 3]
            over pairs(&vec3s(16, 10.0, 7), &vec3s(16, 10.0, 8)), tol ulp_or_abs(2, 4e-5) => {
            [
                a.cross(b), Vec3::splat(a.dot(b)),
                vec3(a.xy().dot(b.xy()), a.extend(1.0).dot(b.extend(-2.0)), b.cross(a).dot(a)),
            ]
        }
        /// Lengths and distances: WGSL inherits `length` from
        /// `sqrt(dot(x, x))` (`sqrt` from `1 / inverseSqrt`, 2 + 2.5 ULP).
        lengths(a: Vec3, b: Vec3) -> [f32; 6] over pairs(&vec3s(16, 10.0, 9), &vec3s(16, 10.0, 10)), tol ulp(8) => {
            [
                a.length(), a.length_squared(), a.distance(b), a.distance_squared(b),
                (a + Vec3::ONE * 20.0).length_recip(), a.xy().length(),
            ]
        }
        /// `normalize` (inherited from `x / length(x)`) and
        /// `normalize_or_zero`.
        normalize(a: Vec3) -> [Vec3; 3] over one(&vec3s(64, 50.0, 11)[1..]), tol ulp(8) => {
            [a.normalize(), a.normalize_or_zero(), (a * 0.0).normalize_or_zero() + a.xy().normalize().extend(1.0)]
        }
        /// `abs`, `min`, `max`, `clamp` (exact).
        abs_min_max_clamp(a: Vec3, b: Vec3) -> [Vec3; 5] over pairs(&vec3s(16, 10.0, 12), &vec3s(16, 10.0, 13)) => {
            [a.abs(), a.min(b), a.max(b), a.clamp(Vec3::splat(-1.0), Vec3::ONE), b.clamp(a.min(b), a.max(b) + 1.0)]
        }
        /// `lerp` is glam's `a * (1 - t) + b * t`, which WGSL's `mix`
        /// inherits its accuracy from; reassociated or fused, the two
        /// products can cancel, so the bound is absolute, a few ULP of
        /// |a| + |b| (here <= 200).
        lerp(a: Vec3, b: Vec3, t: f32) -> [Vec3; 2]
            over triples(&vec3s(8, 100.0, 14), &vec3s(8, 100.0, 15), &[0.0, 1.0, 0.5, 0.25, -0.5]),
            tol ulp_or_abs(4, 6e-5) => {
            [a.lerp(b, t), a.xy().lerp(b.xy(), 1.0 - t).extend(t)]
        }
        /// Rounding (exact): Rust's `round` (half away from zero), `fract`
        /// (`x - trunc(x)`), glam's `fract_gl` (`x - floor(x)`), `signum`
        /// (1 for +0.0; -0.0 is left out, see the top of the file).
        vec3_rounding(a: Vec3) -> [Vec3; 7]
            over one(&vec3s_from_grid().into_iter().map(|v| v + 0.0).collect::<Vec<_>>()) => {
            [a.floor(), a.ceil(), a.round(), a.trunc(), a.fract(), a.fract_gl(), a.signum()]
        }
        /// `powf` (positive bases), `sqrt`, `exp`, `ln`: WGSL's bounds are
        /// the scalar functions' (see `scalar_math`).
        vec3_powers(a: Vec3) -> [Vec3; 4] over one(&vec3s(64, 4.0, 16)), tol ulp_or_abs(64, 2.0f32.powi(-21)) => {
            let p = a.abs() + 0.01;
            [p.powf(1.7), p.sqrt(), a.exp(), p.ln()]
        }
        /// `sin`/`cos` inside `[-pi, pi]`: WGSL, absolute error 2^-11.
        vec3_trig(a: Vec3) -> [Vec3; 2] over one(&vec3s(64, 3.14159, 17)), tol ulp_or_abs(0, 2.0f32.powi(-11)) => {
            [a.sin(), a.cos()]
        }
        /// `mul_add` (WGSL: inherited from `a * b + c`, may be unfused, so
        /// one rounding of the product: absolute, |a * b| <= 100) and
        /// `recip` (2.5 ULP).
        vec3_mul_add_recip(a: Vec3, b: Vec3) -> [Vec3; 2]
            over pairs(&vec3s(16, 10.0, 18), &vec3s_nonzero(16, 19)), tol ulp_or_abs(3, 1e-5) => {
            [a.mul_add(b, Vec3::ONE), b.recip()]
        }
        /// `reflect` and `refract` as methods (WGSL: inherited from their
        /// formulas).
        vec3_reflect_refract(i: Vec3, n: Vec3) -> [Vec3; 3]
            over pairs(&units(16, 20), &units(16, 21)), tol ulp_or_abs(8, 1e-6) => {
            let n = if n.dot(i) > 0.0 { -n } else { n };
            [i.reflect(n), i.refract(n, 1.0 / 1.5), i.refract(n, 1.5)]
        }
        /// `extend`, `truncate` and swizzles (2 to 4 components, repeated).
        swizzles(a: Vec3) -> [Vec4; 6] over one(&vec3s(64, 10.0, 22)) => {
            let h = a.extend(1.0);
            let back = h.truncate().extend(2.0);
            let two = a.xy().extend(a.z).extend(3.0);
            let uv = a.zx() + a.yy();
            [h, back, two, a.xyzx() + a.zzzz(), h.wzyx() + h.xxyy(), vec4(uv.x, uv.y, a.yz().x, a.zyx().y)]
        }
        /// `element_sum`, `element_product`, `min_element`, `max_element` on
        /// `Vec2`, `Vec3`, `Vec4`. The compiler sums left to right; glam's
        /// SSE2 `Vec4` pairwise (`(x + y) + (z + w)`): a rounding apart.
        reductions(a: Vec4) -> [f32; 8] over one(&vec4s(64, 100.0, 23)), tol CHAINED => {
            let b = a.xyz();
            [
                a.element_sum(),
                a.element_product(),
                a.min_element(),
                a.max_element(),
                b.element_sum(),
                b.min_element(),
                a.xy().max_element(),
                a.zw().element_product(),
            ]
        }
        /// `as_ivec*`/`as_uvec*` truncate and saturate per component like
        /// `as i32`/`as u32`; `as_vec*` rounds to nearest.
        float_to_int_vectors(a: Vec3) -> [IVec3; 4] over one(&vec3s_from_grid()) => {
            [
                a.as_ivec3(), a.as_uvec3().as_ivec3(), (a * 0.5).as_ivec3(),
                a.xy().as_ivec2().extend(a.as_uvec3().z as i32),
            ]
        }
        /// `Vec2` and `Vec4` arithmetic and constants.
        vec2_vec4(a: Vec4, b: Vec4) -> [Vec4; 5]
            over pairs(&vec4s(16, 10.0, 24), &vec4s(16, 10.0, 25)), tol CHAINED => {
            let p = a.xy() * b.zw() - Vec2::X + Vec2::NEG_Y;
            [
                a + b * 2.0 - Vec4::W,
                a * b - Vec4::splat(1.5),
                p.extend(1.0).extend(0.0),
                -a.abs() + Vec4::ONE + Vec4::NEG_X,
                a.min(b).max(Vec4::ZERO) + Vec4::Y - Vec4::NEG_ONE + Vec4::NEG_Z,
            ]
        }
    }
}

// ---------------------------------------------------------------------------
// Integer vectors
// ---------------------------------------------------------------------------

differential! {
    /// `IVec*`/`UVec*` operators and methods.
    fn integer_vectors {
        /// Arithmetic on `IVec3`: `+ - *`, `/ %` (truncating), negation,
        /// scalars on either side, compound assignment.
        ivec3_arith(a: IVec3, b: IVec3) -> [IVec3; 6] over pairs(&ivec3s(16, 1000, 26), &ivec3s(16, 1000, 27)) => {
            let d = b.abs() + IVec3::ONE;
            let mut c = a;
            c += b;
            c *= 2;
            c -= IVec3::Z;
            [a + b, a - b * 3, -a * b, a / d, a % d, c]
        }
        /// `abs`, `signum`, `min`, `max`, `clamp`, `dot` and reductions on
        /// `IVec3`.
        ivec3_methods(a: IVec3, b: IVec3) -> [i32; 8] over pairs(&ivec3s(16, 1000, 28), &ivec3s(16, 1000, 29)) => {
            let lo = a.min(b);
            let hi = a.max(b);
            [
                a.abs().element_sum(),
                a.signum().dot(ivec3(1, 10, 100)),
                lo.min_element(),
                hi.max_element(),
                a.clamp(IVec3::splat(-5), IVec3::splat(5)).element_product(),
                a.dot(b),
                b.element_product() / 1000,
                (a - b).min_element(),
            ]
        }
        /// `UVec3` arithmetic, methods and conversions.
        uvec3_ops(a: UVec3, b: UVec3) -> [UVec3; 6] over pairs(&uvec3s(16, 60000, 30), &uvec3s(16, 60000, 31)) => {
            let d = b + UVec3::ONE;
            let mut c = a;
            c *= 3;
            c %= 1000;
            [
                a + b, a.max(b) - a.min(b), a * 2 + b / d, a % d, c + UVec3::Y,
                UVec3::splat(a.dot(UVec3::ONE) + b.element_sum()),
            ]
        }
        /// Conversions between vector types: `as_vec*`, `as_ivec*`,
        /// `as_uvec*` (bit-preserving between the integer types).
        int_vector_conversions(a: IVec3) -> [Vec3; 4] over one(&ivec3s(64, i32::MAX, 32)) => {
            let u = a.as_uvec3();
            [a.as_vec3(), u.as_vec3(), u.as_ivec3().as_vec3() - a.as_vec3(), (a >> 8u32).as_vec3() * 0.5]
        }
        /// Pixel-grid math on `launch_index()`-like `UVec2`s.
        uvec2_grid(a: UVec2, b: UVec2) -> [UVec2; 4] over pairs(
            &random(16, 33, |x| uvec2(x % 640, (x >> 16) % 480)),
            &random(16, 34, |x| uvec2(x % 16 + 1, (x >> 8) % 16 + 1))
        ) => {
            let tile = a / b;
            let within = a % b;
            let checker = (tile.x + tile.y) & 1;
            [tile, within, UVec2::splat(checker), (a << 1u32) ^ (b >> UVec2::splat(2)) | uvec2(1, 2) & !UVec2::ZERO]
        }
    }
}

// ---------------------------------------------------------------------------
// Matrices
// ---------------------------------------------------------------------------

differential! {
    /// `Mat3`/`Mat4`: constructors, constants, products with vectors,
    /// matrices and scalars, `transpose`, `determinant`, columns.
    fn matrices {
        /// `Mat3 * Vec3` and `mul_vec3` (WGSL: sums of products in any
        /// order, possibly fused: absolute, terms <= 40).
        mat3_vec3(m: Mat3, v: Vec3) -> [Vec3; 4]
            over pairs(&mat3s(16, 50), &vec3s(16, 10.0, 51)), tol ulp_or_abs(2, 2e-5) => {
            [m * v, m.mul_vec3(v), m.transpose() * v, Mat3::from_diagonal(v) * m.col(1)]
        }
        /// `Mat3` products, sums, scalar products (exact for `+ -` and
        /// scalars; products absolute, terms <= 16).
        mat3_mat3(a: Mat3, b: Mat3) -> [Mat3; 5]
            over pairs(&mat3s(16, 52), &mat3s(16, 53)), tol ulp_or_abs(2, 1e-5) => {
            [
                a * b, a.mul_mat3(&b), a + b - Mat3::IDENTITY, a * 2.0 + 0.5 * b,
                a.transpose() * Mat3::ZERO + Mat3::from_cols(b.z_axis, a.x_axis, b.y_axis),
            ]
        }
        /// `determinant` (WGSL gives no bound; ~30 ULP of the largest
        /// product, |det| <= 400), columns by field and by `col`.
        mat3_det_cols(m: Mat3) -> [f32; 4] over one(&mat3s(64, 54)), tol ulp_or_abs(4, 1e-3) => {
            [m.determinant(), m.x_axis.y + m.col(2).z, m.transpose().y_axis.x, m.col(0).dot(m.z_axis)]
        }
        /// `Mat4 * Vec4`, `mul_vec4`, `transform_point3`,
        /// `transform_vector3` (terms <= 40).
        mat4_vec(m: Mat4, v: Vec4) -> [Vec4; 4]
            over pairs(&mat4s(16, 55), &vec4s(16, 10.0, 56)), tol ulp_or_abs(2, 3e-5) => {
            [
                m * v, m.mul_vec4(v), m.transform_point3(v.xyz()).extend(0.0),
                m.transform_vector3(v.xyz()).extend(m.w_axis.w),
            ]
        }
        /// `Mat4` products, transposes and sums.
        mat4_mat4(a: Mat4, b: Mat4) -> [Mat4; 3]
            over pairs(&mat4s(16, 57), &mat4s(16, 58)), tol ulp_or_abs(2, 2e-5) => {
            [a * b, a.mul_mat4(&b).transpose(), a * Mat4::IDENTITY + Mat4::ZERO - b * 0.5]
        }
        /// `Mat4::determinant` (no WGSL bound; |det| <= 6e3).
        mat4_det(m: Mat4) -> [f32; 2] over one(&mat4s(64, 59)), tol ulp_or_abs(4, 2e-2) => {
            [m.determinant(), m.x_axis.truncate().length_squared()]
        }
    }
}
