//! Integer edge cases and spot checks against values worked out by hand.

use super::*;

// The programs the spot checks launch again.
use super::control_flow::{match_i32, while_loop};
use super::math::{powi, rounding, sign_min_max};
use super::scalars::{f32_rem, f32_to_i32, f32_to_u32, i32_div_rem, i32_shifts, i32_to_f32, u32_bit_counts};

// ---------------------------------------------------------------------------
// Integer edge cases
// ---------------------------------------------------------------------------

differential! {
    /// The integer results Rust defines at the edges of the range, which the
    /// compiler must keep: constants, `abs` and `signum`, division by -1 and
    /// by the minimum, shifts of the extremes, and `as` between signedness.
    fn integer_edges {
        /// `i32::MIN`/`MAX`, `u32::MAX` and `MIN` constants in arithmetic.
        limits(a: i32) -> [i32; 5] over one(&I16) => {
            [
                i32::MAX - a.abs(), i32::MIN + a.abs(), (u32::MAX - a.abs() as u32) as i32, u32::MIN as i32 + a,
                i32::MAX.wrapping_add(a),
            ]
        }
        /// `abs` and `signum` over the range (not `i32::MIN.abs()`, which
        /// overflows).
        abs_signum(a: i32) -> [i32; 2]
            over one(&i64_grid().into_iter().filter(|&a| a != i32::MIN).collect::<Vec<_>>()) => {
            [a.abs(), a.signum()]
        }
        /// Division and remainder at the edges: by 1, -1 (not of
        /// `i32::MIN`), `i32::MIN` and `i32::MAX`.
        div_edges(a: i32, b: i32) -> [i32; 2]
            over pairs_where(&I32_EDGES, &[1, -1, i32::MIN, i32::MAX, 2, -2], |a, b| !(a == i32::MIN && b == -1)) => {
            [a / b, a % b]
        }
        /// Shifts of the extremes (sign bit in and out).
        shift_edges(s: u32) -> [i32; 4] over one(&shifts()) => {
            [i32::MIN >> s, i32::MAX >> s, -1 << s, (u32::MAX >> s) as i32]
        }
        /// Wrapping arithmetic at the edges.
        wrap_edges(a: i32) -> [u32; 4] over one(&I32_EDGES) => {
            [
                a.wrapping_add(i32::MAX) as u32, a.wrapping_mul(-1) as u32, (a as u32).wrapping_sub(1),
                (a as u32).wrapping_mul(0x9e37_79b9),
            ]
        }
    }
}

// ---------------------------------------------------------------------------
// Spot checks against values worked out by hand
// ---------------------------------------------------------------------------

/// `%=` on buffer elements, a field of one, and a vector element, in place.
#[rt_program(ray_generation)]
pub fn rem_in_place(#[var] mut io: RwBuffer<f32>, #[var] mut iov: RwBuffer<Vec3>, #[var] top: Object) {
    let idx = launch_index().x;
    keep_scene_binding(top, idx);
    io[idx] %= 0.1;
    iov[idx].y %= 0.3;
    iov[idx] %= Vec3::new(2.0, 0.7, 0.25);
}

/// Results Rust defines and the compiler must reproduce, written down (not
/// computed): checked on both backends, they pin the CPU reference itself.
#[test]
fn spot_checks_against_known_values() {
    let mut h = Harness::new();
    // Rust's rounding flavours: `round` half away from zero, `round_ties_even`,
    // `fract` keeps the sign.
    h.expect::<(f32,), f32, 6>(
        &rounding::rounding::PROGRAM,
        &["x"],
        &[
            ((0.5,), [0.0, 1.0, 0.0, 1.0, 0.0, 0.5]),
            ((-0.5,), [-1.0, -0.0, -0.0, -1.0, -0.0, -0.5]),
            ((2.5,), [2.0, 3.0, 2.0, 3.0, 2.0, 0.5]),
            ((-2.5,), [-3.0, -2.0, -2.0, -3.0, -2.0, -0.5]),
            ((0.49999997,), [0.0, 1.0, 0.0, 0.0, 0.0, 0.49999997]),
            ((-1.25,), [-2.0, -1.0, -1.0, -1.0, -1.0, -0.25]),
            ((8388609.0,), [8388609.0, 8388609.0, 8388609.0, 8388609.0, 8388609.0, 0.0]),
        ],
    );
    // `signum` of zeros, `min`/`max`/`clamp`.
    h.expect::<(f32, f32), f32, 7>(
        &sign_min_max::sign_min_max::PROGRAM,
        &["x", "y"],
        &[
            ((0.0, 1.0), [0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0]),
            ((-0.5, 7.0), [0.5, -1.0, -0.5, 7.0, -0.5, 0.0, PI]),
            ((-3.0, -4.0), [3.0, -1.0, -4.0, -3.0, -1.0, 0.0, -4.0]),
        ],
    );
    // Float `%` is the exact remainder with the dividend's sign.
    h.expect::<(f32, f32), f32, 2>(
        &f32_rem::f32_rem::PROGRAM,
        &["a", "b"],
        &[
            ((7.5, 2.0), [1.5, 0.5]),
            ((-7.5, 2.0), [-1.5, -0.5]),
            ((1.0, 0.1), [0.09999998658895493, 0.09999995678663254]),
            ((3.0e7, 0.1), [0.05296517163515091, 0.05889551341533661]),
            ((5.0, 5.0), [0.0, 0.0]),
        ],
    );
    // Integer division truncates; `%` takes the dividend's sign.
    h.expect::<(i32, i32), i32, 2>(
        &i32_div_rem::i32_div_rem::PROGRAM,
        &["a", "b"],
        &[
            ((-7, 3), [-2, -1]),
            ((7, -7), [-1, 0]),
            ((-8, 3), [-2, -2]),
            ((i32::MIN, -7), [306783378, -2]),
            ((5, i32::MIN), [0, 5]),
        ],
    );
    // Arithmetic right shift of negative values.
    h.expect::<(i32, u32), i32, 5>(
        &i32_shifts::i32_shifts::PROGRAM,
        &["a", "s"],
        &[((-16, 2), [-64, -4, -64, -4, -16]), ((i32::MIN, 31), [0, -1, 0, -1, 0]), ((-1, 0), [-1, -1, -1, -1, -1])],
    );
    // Float to integer casts truncate and saturate.
    h.expect::<(f32,), i32, 2>(
        &f32_to_i32::f32_to_i32::PROGRAM,
        &["x"],
        &[
            ((2.9,), [2, 1]),
            ((-2.9,), [-2, -1]),
            ((3.0e9,), [i32::MAX, 1_500_000_000]),
            ((-3.0e9,), [i32::MIN, -1_500_000_000]),
            ((1.0e20,), [i32::MAX, i32::MAX]),
        ],
    );
    h.expect::<(f32,), u32, 2>(
        &f32_to_u32::f32_to_u32::PROGRAM,
        &["x"],
        &[((-1.5,), [0, 1]), ((5.0e9,), [u32::MAX, 0]), ((-5.0e9,), [0, u32::MAX]), ((4294967040.0,), [4294967040, 0])],
    );
    // Integer to float rounds to nearest, ties to even.
    h.expect::<(i32,), f32, 2>(
        &i32_to_f32::i32_to_f32::PROGRAM,
        &["a"],
        &[((16777217,), [16777216.0, 5592405.0]), ((16777219,), [16777220.0, 5592406.0]), ((-7,), [-7.0, -2.0])],
    );
    // `powi` of a negative base.
    h.expect::<(f32, i32), f32, 1>(
        &powi::powi::PROGRAM,
        &["x", "n"],
        &[((-0.5, 2), [0.25]), ((-2.0, 3), [-8.0]), ((2.0, -2), [0.25]), ((3.0, 0), [1.0])],
    );
    // Bit counts and the hash of known values.
    h.expect::<(u32,), u32, 4>(
        &u32_bit_counts::u32_bit_counts::PROGRAM,
        &["a"],
        &[((0,), [0, 32, 32, 0]), ((1,), [1, 31, 0, 0x8000_0000]), ((0xf0,), [4, 24, 4, 0x0f00_0000])],
    );
    // Collatz from 27: 111 steps, peak 9232.
    h.expect::<(u32,), u32, 2>(
        &while_loop::while_loop::PROGRAM,
        &["n"],
        &[((27,), [111, 9232]), ((1,), [0, 1]), ((6,), [8, 16])],
    );
    // `match` arms.
    h.expect::<(i32,), i32, 3>(
        &match_i32::match_i32::PROGRAM,
        &["a"],
        &[((0,), [100, 1, 1]), ((-3,), [300, 0, -332]), ((11,), [400, 7, 91]), ((-5,), [500, -10, -199])],
    );
    h.finish();

    // In-place `%=` through buffer element places.
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let backend = on.name();
        let mut ctx = Harness::context(on);
        let ctx = &mut ctx;
        let p = ctx.create_program(&rem_in_place::PROGRAM);
        let io = ctx.create_buffer(BufferType::InputOutput, vec![1.0f32, -7.5, 0.25]);
        let iov =
            ctx.create_buffer(BufferType::InputOutput, vec![vec3(5.0, 1.0, -0.3), vec3(-3.0, 0.65, 0.5), Vec3::ZERO]);
        ctx.set_var(p, "io", io).unwrap();
        ctx.set_var(p, "iov", iov).unwrap();
        ctx.set_ray_generation_program(0, p).unwrap();
        ctx.launch(0, 3, 1).unwrap();
        assert_eq!(
            ctx.read_buffer::<f32>(io).unwrap(),
            vec![0.09999998658895493, -0.09999988973140717, 0.04999999701976776],
            "{backend:?}"
        );
        let v = ctx.read_buffer::<Vec3>(iov).unwrap();
        assert_eq!(
            v,
            vec![
                vec3(1.0, 0.09999996423721313, -0.050000011920928955),
                vec3(-1.0, 0.04999995231628418, 0.0),
                Vec3::ZERO
            ],
            "{backend:?}"
        );
    }
}
