//! std's methods of `i32`, `u32` and `f32` that `builtins/std_scalars.rs`
//! writes out (and `f32::from_bits`, `from_be`/`from_le`), on both
//! backends, over inputs where std does not panic (`tests/integer_semantics.rs`
//! has the GPU's meaning where it would).

use super::*;

const AMOUNTS: [u32; 7] = [0, 1, 5, 31, 32, 33, 100];
const EXPONENTS: [u32; 8] = [0, 1, 2, 3, 7, 31, 32, 1000];

differential! {
    /// Integers.
    fn std_ints {
        /// Bit counts, shifts, negation and `abs` forms, signs, byte
        /// order, sign casts.
        bits_and_shifts(a: i32, n: u32) -> [u32; 12] over pairs(&I32_EDGES, &AMOUNTS) => {
            let u = a as u32;
            [
                a.count_zeros() | (u.count_zeros() << 8) | (a.leading_ones() << 16) | (u.trailing_ones() << 24),
                a.wrapping_shl(n) as u32,
                a.wrapping_shr(n) as u32 ^ u.wrapping_shr(n).rotate_left(3),
                a.unbounded_shl(n) as u32 ^ u.unbounded_shr(n).rotate_left(7),
                a.unbounded_shr(n) as u32,
                a.overflowing_shl(n).0 as u32 ^ (a.overflowing_shr(n).1 as u32) ^ ((u.overflowing_shl(n).1 as u32) << 1),
                a.wrapping_neg() as u32 ^ u.wrapping_neg().rotate_left(3),
                a.wrapping_abs() as u32 ^ a.unsigned_abs().rotate_left(5),
                a.saturating_neg() as u32 ^ (a.saturating_abs() as u32).rotate_left(9),
                (a.overflowing_neg().1 as u32) | ((u.overflowing_neg().1 as u32) << 1) | ((a.overflowing_abs().1 as u32) << 2)
                    | ((a.is_positive() as u32) << 3) | ((a.is_negative() as u32) << 4)
                    | ((a.overflowing_neg().0 as u32 ^ u.overflowing_neg().0) & 0xffff00),
                a.to_be() as u32 ^ u.to_be().rotate_left(1) ^ (i32::from_be(a) as u32).rotate_left(2) ^ u32::from_le(u) ^ (a.to_le() as u32),
                a.cast_unsigned() ^ (u.cast_signed() as u32).rotate_left(4),
            ]
        }
        /// Differences, means, remainders (non-zero divisors), products
        /// with their overflow, `div_ceil`, `next_multiple_of`, signed
        /// addition to a `u32`.
        arithmetic(a: i32, b: i32) -> [u32; 14] over pairs(&I32_EDGES, &I32_EDGES) => {
            let (u, v) = (a as u32, b as u32);
            [
                a.abs_diff(b) ^ u.abs_diff(v).rotate_left(11),
                a.midpoint(b) as u32,
                u.midpoint(v),
                a.wrapping_rem(b | 1) as u32 ^ u.wrapping_rem(v | 1).rotate_left(6),
                a.wrapping_div_euclid(b | 1) as u32 ^ (a.wrapping_rem_euclid(b | 1) as u32).rotate_left(9),
                u.wrapping_div_euclid(v | 1) ^ u.wrapping_rem_euclid(v | 1).rotate_left(9),
                a.overflowing_mul(b).0 as u32 ^ ((a.overflowing_mul(b).1 as u32) << 31) ^ ((u.overflowing_mul(v).1 as u32) << 30),
                u.overflowing_mul(v).0,
                u.div_ceil(v | 1) ^ (u >> 1).next_multiple_of((v >> 16) | 1).rotate_left(5),
                u.overflowing_add_signed(b).0 ^ (u.overflowing_add_signed(b).1 as u32).rotate_left(13),
                a.overflowing_add_unsigned(v).0 as u32 ^ ((a.overflowing_add_unsigned(v).1 as u32) << 31)
                    ^ ((a.overflowing_sub_unsigned(v).1 as u32) << 30) ^ (a.overflowing_sub_unsigned(v).0 as u32).rotate_left(7),
                a.overflowing_div(b | 1).0 as u32 ^ ((a.overflowing_div(b | 1).1 as u32) << 31)
                    ^ (a.overflowing_rem(b | 1).0 as u32).rotate_left(5) ^ ((a.overflowing_rem(b | 1).1 as u32) << 30),
                a.overflowing_div_euclid(b | 1).0 as u32 ^ ((a.overflowing_div_euclid(b | 1).1 as u32) << 31)
                    ^ (a.overflowing_rem_euclid(b | 1).0 as u32).rotate_left(5) ^ ((a.overflowing_rem_euclid(b | 1).1 as u32) << 30),
                u.overflowing_div(v | 1).0 ^ u.overflowing_rem(v | 1).0.rotate_left(3) ^ u.overflowing_div_euclid(v | 1).0.rotate_left(6)
                    ^ u.overflowing_rem_euclid(v | 1).0.rotate_left(9)
                    ^ ((u.overflowing_div(v | 1).1 | u.overflowing_rem_euclid(v | 1).1) as u32),
            ]
        }
        /// Powers (wrapping, overflowing, saturating), integer roots and
        /// logarithms, `next_power_of_two`.
        powers_and_logs(a: i32, e: u32) -> [u32; 8] over pairs(&I32_EDGES, &EXPONENTS) => {
            let u = a as u32;
            [
                a.wrapping_pow(e) as u32 ^ u.wrapping_pow(e).rotate_left(13),
                a.overflowing_pow(e).0 as u32 ^ ((a.overflowing_pow(e).1 as u32) << 31) ^ ((u.overflowing_pow(e).1 as u32) << 30),
                u.overflowing_pow(e).0,
                a.saturating_pow(e) as u32 ^ u.saturating_pow(e).rotate_left(3),
                (a & 3).pow(e % 16) as u32 ^ ((u & 3).pow(e % 16)).rotate_left(1),
                u.isqrt() ^ ((a & 0x7fff_ffff).isqrt() as u32).rotate_left(16),
                (u | 1).ilog2() | ((u | 1).ilog10() << 8) | ((u | 1).ilog(e.max(2)) << 16) | (((a & 0x7fff_ffff) | 1).ilog(3) << 24),
                (u >> 1).next_power_of_two() ^ (((a & 0x7fff_ffff) | 1).ilog2() + ((a & 0x7fff_ffff) | 1).ilog10()),
            ]
        }
    }
}

differential! {
    /// Floats.
    fn std_floats {
        /// Bits, sign and class tests, `from_bits`, the neighbours.
        bits(x: f32) -> [u32; 4] over one(&f64_grid()) => {
            [
                x.to_bits(),
                (x.is_sign_positive() as u32) | ((x.is_sign_negative() as u32) << 1) | ((x.is_normal() as u32) << 2)
                    | ((x.is_subnormal() as u32) << 3) | (((x * 1e-38).is_normal() as u32) << 4),
                f32::from_bits(x.to_bits() ^ 0x8000_0000).to_bits(),
                x.next_up().to_bits() ^ x.next_down().to_bits().rotate_left(16),
            ]
        }
        /// `exp_m1` and `ln_1p` (as `exp(x) - 1` and `log(1 + x)`: WGSL's
        /// accuracy of each, absolute near 0), `cbrt` (through `pow`),
        /// `midpoint` (exact).
        formulas(x: f32, y: f32) -> [f32; 4] over pairs(&spread(12, -4.0, 4.0), &spread(5, -3.0, 3.0)), tol ulp_or_abs(64, 1e-4) => {
            [x.exp_m1(), x.abs().ln_1p(), (x * y).cbrt(), x.midpoint(y)]
        }
    }
}
