//! The dividing methods of the integers (`div_euclid`, `rem_euclid`,
//! `wrapping_div`, `saturating_div`) on both backends: against plain Rust
//! where Rust answers, and against values worked out by hand where it
//! panics (a zero divisor, `i32::MIN / -1`), which both backends answer as
//! WGSL's `/` and `%` do (`rt_std::arith`).

use super::*;

/// Neither a zero divisor nor `i32::MIN / -1`, either way round (the
/// vector programs divide `a` by `b` and `b` by `a`).
fn rust_answers(a: i32, b: i32) -> bool {
    a != 0 && b != 0 && !(a == i32::MIN && b == -1) && !(b == i32::MIN && a == -1)
}

differential! {
    /// Where Rust answers, both backends answer as Rust does.
    fn int_division_as_rust {
        /// The four methods of `i32`, method and path forms.
        div_i32(a: i32, b: i32) -> [i32; 5] over pairs_where(&I32_EDGES, &I32_EDGES, rust_answers) => {
            [a.div_euclid(b), a.rem_euclid(b), a.wrapping_div(b), a.saturating_div(b), i32::rem_euclid(b, a)]
        }
        /// And of `u32`.
        div_u32(a: u32, b: u32) -> [u32; 5] over pairs_where(&U32_EDGES, &U32_EDGES, |a, b| a != 0 && b != 0) => {
            [a.div_euclid(b), a.rem_euclid(b), a.wrapping_div(b), a.saturating_div(b), u32::div_euclid(b, a)]
        }
        /// Per component, on `IVec2`/`IVec3`/`IVec4`.
        div_ivec(a: i32, b: i32) -> [IVec4; 6] over pairs_where(&I32_EDGES, &I32_EDGES, rust_answers) => {
            let v = ivec4(a, b, 7, -7);
            let w = ivec4(b, a, b, b);
            [
                v.div_euclid(w),
                v.rem_euclid(w),
                v.wrapping_div(w),
                v.saturating_div(w),
                v.truncate().div_euclid(w.truncate()).extend(IVec2::rem_euclid(v.xy(), w.zw()).x),
                v.xy().saturating_div(w.yx()).extend(0).extend(v.zw().wrapping_div(w.xy()).y),
            ]
        }
        /// And on `UVec2`/`UVec3`/`UVec4`.
        /// (glam's `UVecN` has no `div_euclid`/`rem_euclid`.)
        div_uvec(a: u32, b: u32) -> [UVec4; 3] over pairs_where(&U32_EDGES, &U32_EDGES, |a, b| a != 0 && b != 0) => {
            let v = uvec4(a, b, 7, 3_000_000_000);
            let w = uvec4(b, a, b, b);
            [
                v.wrapping_div(w),
                v.saturating_div(w),
                v.truncate().saturating_div(w.truncate()).extend(v.xy().wrapping_div(w.yx()).y),
            ]
        }
    }
}

/// Constant operands, which WGSL would evaluate when the shader is created
/// (where a zero divisor and `i32::MIN / -1` are errors): the lowering's
/// functions take them as values at run time.
#[rt_program(ray_generation)]
pub fn div_constants(#[var] a: Buffer<i32>, #[var] mut out: RwBuffer<i32>, #[var] top: Object) {
    let idx = launch_index().x;
    keep_scene_binding(top, idx);
    let a = a[idx];
    out[idx * 6] = a.div_euclid(0);
    out[idx * 6 + 1] = 7i32.rem_euclid(0);
    out[idx * 6 + 2] = i32::MIN.wrapping_div(-1);
    out[idx * 6 + 3] = i32::MIN.saturating_div(-1);
    out[idx * 6 + 4] = i32::MIN.div_euclid(-1);
    out[idx * 6 + 5] = (5u32.div_euclid(0) + 9u32.rem_euclid(0)) as i32;
}

/// Where Rust panics, both backends give WGSL's answers: a zero divisor is
/// read as one (the quotients are the dividend, the remainder 0), and
/// `i32::MIN / -1` wraps (`saturating_div`: `i32::MAX`).
#[test]
fn int_division_where_rust_panics() {
    const MIN: i32 = i32::MIN;
    const MAX: i32 = i32::MAX;
    let mut h = Harness::new();
    h.expect::<(i32, i32), i32, 5>(
        &div_i32::div_i32::PROGRAM,
        &["a", "b"],
        &[
            ((7, 0), [7, 0, 7, 7, 0]),
            ((-7, 0), [-7, 0, -7, -7, 0]),
            ((0, 5), [0, 0, 0, 0, 0]),
            ((MIN, -1), [MIN, 0, MIN, MAX, MAX]),
            ((MIN, 0), [MIN, 0, MIN, MIN, 0]),
            ((-7, 2), [-4, 1, -3, -3, 2]),
            ((-7, -2), [4, 1, 3, 3, 5]),
            ((-1, MIN), [1, MAX, 0, 0, 0]),
        ],
    );
    h.expect::<(u32, u32), u32, 5>(
        &div_u32::div_u32::PROGRAM,
        &["a", "b"],
        &[((9, 0), [9, 0, 9, 9, 0]), ((u32::MAX, 0), [u32::MAX, 0, u32::MAX, u32::MAX, 0]), ((9, 4), [2, 1, 2, 2, 0])],
    );
    h.expect::<(i32, i32), IVec4, 6>(
        &div_ivec::div_ivec::PROGRAM,
        &["a", "b"],
        &[
            (
                (MIN, -1),
                [
                    ivec4(MIN, 1, -7, 7),
                    ivec4(0, MAX, 0, 0),
                    ivec4(MIN, 0, -7, 7),
                    ivec4(MAX, 0, -7, 7),
                    ivec4(MIN, 1, -7, 0),
                    ivec4(1, 1, 0, 0),
                ],
            ),
            (
                (5, 0),
                [
                    ivec4(5, 0, 7, -7),
                    ivec4(0, 0, 0, 0),
                    ivec4(5, 0, 7, -7),
                    ivec4(5, 0, 7, -7),
                    ivec4(5, 0, 7, 0),
                    ivec4(1, 0, 0, -1),
                ],
            ),
        ],
    );
    h.expect::<(u32, u32), UVec4, 3>(
        &div_uvec::div_uvec::PROGRAM,
        &["a", "b"],
        &[((9, 0), [uvec4(9, 0, 7, 3_000_000_000), uvec4(9, 0, 7, 3_000_000_000), uvec4(9, 0, 7, 0)])],
    );
    h.expect::<(i32,), i32, 6>(
        &div_constants::PROGRAM,
        &["a"],
        &[((-3,), [-3, 0, MIN, MAX, MIN, 5]), ((MIN,), [MIN, 0, MIN, MAX, MIN, 5])],
    );
    h.finish();
}
