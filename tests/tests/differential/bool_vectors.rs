//! Bool vectors on both backends: glam's comparisons and masks of the
//! numeric vectors, the `BVec` operators and methods, `VecN::select`, and
//! `BVec` helper parameters and results. A mask leaves a program as its
//! `bitmask()` (bools are never stored).

use super::*;

/// Where any component of `p` is below `lo` or above `hi`: a `BVec3`
/// through a helper.
#[rt_function]
pub fn outside(p: Vec3, lo: Vec3, hi: Vec3) -> BVec3 {
    p.cmplt(lo) | p.cmpgt(hi)
}

#[rt_function]
pub fn flip(m: BVec4A, which: u32) -> BVec4A {
    m ^ BVec4A::new(which & 1 != 0, which & 2 != 0, which & 4 != 0, which & 8 != 0)
}

/// Special values for the masks: zeros of both signs, infinities, NaN.
fn specials() -> Vec<Vec4> {
    let (inf, nan) = (f32::INFINITY, f32::NAN);
    vec![
        vec4(0.0, -0.0, 1.0, -1.0),
        vec4(inf, -inf, nan, -nan),
        vec4(f32::MAX, f32::MIN, f32::MIN_POSITIVE, -1e-45),
        vec4(nan, 2.0, -inf, 0.0),
    ]
}

fn vec4_rows() -> Vec<Vec4> {
    let mut v = specials();
    v.extend(vec4s(12, 2.0, 61));
    v.push(vec4(1.0, 2.0, 3.0, 4.0));
    v
}

differential! {
    /// Float vectors.
    fn bool_vectors_float {
        /// The six comparisons of `Vec2`/`Vec3`/`Vec4` (a NaN compares
        /// false, but `cmpne` true), as bitmasks.
        float_comparisons(a: Vec4, b: Vec4) -> [u32; 6] over pairs(&vec4_rows(), &vec4_rows()) => {
            let (a3, b3, a2, b2) = (a.truncate(), b.truncate(), a.truncate().truncate(), b.truncate().truncate());
            [
                a.cmpeq(b).bitmask() | (a3.cmpeq(b3).bitmask() << 4) | (a2.cmpeq(b2).bitmask() << 8),
                a.cmpne(b).bitmask() | (a3.cmpne(b3).bitmask() << 4) | (a2.cmpne(b2).bitmask() << 8),
                a.cmpge(b).bitmask() | (a3.cmpge(b3).bitmask() << 4) | (a2.cmpge(b2).bitmask() << 8),
                a.cmpgt(b).bitmask() | (a3.cmpgt(b3).bitmask() << 4) | (a2.cmpgt(b2).bitmask() << 8),
                a.cmple(b).bitmask() | (a3.cmple(b3).bitmask() << 4) | (a2.cmple(b2).bitmask() << 8),
                a.cmplt(b).bitmask() | (a3.cmplt(b3).bitmask() << 4) | (a2.cmplt(b2).bitmask() << 8),
            ]
        }
        /// `is_negative_mask` (the sign bit: -0.0 and -NaN count),
        /// `is_finite_mask`, `is_nan_mask`.
        float_masks(a: Vec4) -> [u32; 3] over one(&vec4_rows()) => {
            let (a3, a2) = (a.truncate(), a.truncate().truncate());
            [
                a.is_negative_mask().bitmask() | (a3.is_negative_mask().bitmask() << 4) | (a2.is_negative_mask().bitmask() << 8),
                a.is_finite_mask().bitmask() | (a3.is_finite_mask().bitmask() << 4) | (a2.is_finite_mask().bitmask() << 8),
                a.is_nan_mask().bitmask() | (a3.is_nan_mask().bitmask() << 4) | (a2.is_nan_mask().bitmask() << 8),
            ]
        }
        /// `select` by a mask, and a mask through helpers.
        float_select(a: Vec4, b: Vec4) -> [Vec4; 3] over pairs(&vec4s(10, 2.0, 62), &vec4s(6, 2.0, 63)) => {
            let m = flip(a.cmplt(b), 5);
            let away = outside(a.truncate(), Vec3::splat(-1.0), Vec3::ONE);
            [
                Vec4::select(m, a, b),
                Vec3::select(away, a.truncate(), Vec3::ZERO).extend(away.bitmask() as f32),
                Vec2::select(a.truncate().truncate().cmpge(Vec2::ZERO), Vec2::ONE, Vec2::NEG_ONE).extend(0.0).extend(m.bitmask() as f32),
            ]
        }
    }
}

differential! {
    /// Integer vectors and the `BVec` operators and methods.
    fn bool_vectors_int {
        /// The comparisons of `IVec`/`UVec`, `is_negative_mask` of `IVec`.
        int_comparisons(a: i32, b: i32) -> [u32; 4] over pairs(&I32_EDGES, &I32_EDGES) => {
            let v = ivec4(a, b, 0, -1);
            let w = ivec4(b, a, a, b);
            let (u, x) = (v.as_uvec4(), w.as_uvec4());
            [
                v.cmpeq(w).bitmask() | (v.cmpne(w).bitmask() << 4) | (v.cmpge(w).bitmask() << 8) | (v.cmpgt(w).bitmask() << 12)
                    | (v.cmple(w).bitmask() << 16) | (v.cmplt(w).bitmask() << 20) | (v.is_negative_mask().bitmask() << 24),
                u.cmpeq(x).bitmask() | (u.cmpne(x).bitmask() << 4) | (u.cmpge(x).bitmask() << 8) | (u.cmpgt(x).bitmask() << 12)
                    | (u.cmple(x).bitmask() << 16) | (u.cmplt(x).bitmask() << 20),
                v.truncate().cmplt(w.truncate()).bitmask() | (v.xy().cmpge(w.xy()).bitmask() << 4)
                    | (u.truncate().cmpgt(x.truncate()).bitmask() << 8) | (u.xy().cmpne(x.xy()).bitmask() << 12)
                    | (v.truncate().is_negative_mask().bitmask() << 16) | (v.xy().is_negative_mask().bitmask() << 20),
                (IVec4::select(v.cmpgt(w), v, w).w as u32) ^ (IVec4::select(v.cmpgt(w), v, w).x as u32) ^ UVec3::select(u.truncate().cmple(x.truncate()), u.truncate(), x.truncate()).x,
            ]
        }
        /// `&`, `|`, `^`, `!`, `==`, `!=` (also compound), `any`, `all`,
        /// `new`, `splat`, `bvecN`.
        mask_operators(a: u32, b: u32) -> [u32; 4] over pairs(&U16, &U16) => {
            let m = bvec4(a & 1 != 0, a & 2 != 0, a & 4 != 0, a & 8 != 0);
            let n = BVec4::new(b & 1 != 0, b & 2 != 0, b & 4 != 0, b & 8 != 0);
            let mut k = m & n;
            k |= !m & BVec4::splat(b > 100);
            k ^= BVec4::new(true, false, false, true);
            let m3 = BVec3::new(m.x, m.y, m.z);
            let m2 = BVec2::splat(a > b) | bvec2(false, a == 0);
            [
                (m & n).bitmask() | ((m | n).bitmask() << 4) | ((m ^ n).bitmask() << 8) | ((!m).bitmask() << 12) | (k.bitmask() << 16),
                m.any() as u32 | ((m.all() as u32) << 1) | ((m3.any() as u32) << 2) | ((m3.all() as u32) << 3)
                    | ((m2.any() as u32) << 4) | ((m2.all() as u32) << 5),
                (m == n) as u32 | (((m != n) as u32) << 1) | (((m3 == bvec3(true, false, true)) as u32) << 2),
                m3.bitmask() | (m2.bitmask() << 3) | ((!m3 ^ bvec3(true, true, false)).bitmask() << 5),
            ]
        }
    }
}

differential! {
    /// `==` and `!=` on floats where a NaN is: Rust's `!=` is true
    /// (unordered), its `==` false, on scalars, on whole vectors and on a
    /// value against itself.
    fn float_equality_with_nan {
        equality(a: Vec4, b: Vec4) -> [u32; 4] over pairs(&specials(), &specials()) => {
            [
                (a.x != b.x) as u32 | ((a.y != b.y) as u32) << 1 | ((a.z != b.z) as u32) << 2 | ((a.w != b.w) as u32) << 3,
                (a.x == b.x) as u32 | ((a.y == b.y) as u32) << 1 | ((a.z == b.z) as u32) << 2 | ((a.w == b.w) as u32) << 3,
                (a != b) as u32 | ((a == b) as u32) << 1 | ((a.truncate() != b.truncate()) as u32) << 2 | ((a.truncate() == b.truncate()) as u32) << 3,
                (a.z != a.z) as u32 | ((a.x != a.x) as u32) << 1 | ((a != a) as u32) << 2 | ((a == a) as u32) << 3,
            ]
        }
    }
}
