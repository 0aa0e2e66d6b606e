//! Scalar operators: arithmetic, comparison and logic, bits and shifts, casts.

use super::*;

// ---------------------------------------------------------------------------
// Arithmetic
// ---------------------------------------------------------------------------

differential! {
    /// `+ - * / %`, unary minus, compound assignment and literal typing on
    /// every scalar type.
    fn arithmetic {
        /// `+ - *` and negation: correctly rounded in WGSL (the last result
        /// chains two operations, hence [`CHAINED`]).
        f32_add_sub_mul(a: f32, b: f32) -> [f32; 5] over pairs(&F16, &F16), tol CHAINED => {
            [a + b, a - b, a * b, -a, -(a * b) + b]
        }
        /// `/`: WGSL bounds it by 2.5 ULP for |b| in [2^-126, 2^126].
        f32_div(a: f32, b: f32) -> [f32; 2] over pairs_where(&F16, &F16, |_, b| b != 0.0), tol ulp(3) => {
            [a / b, (a + 1.0) / b]
        }
        /// `%` is Rust's exact remainder with the dividend's sign (`fmod`).
        /// WGSL's `%` is `a - b * trunc(a / b)`, a whole `b` off where
        /// `a / b` rounds up to an integer (`1.0 % 0.1`: 0.1 vs 0), so the
        /// compiler lowers `%` on floats to an exact `fmod`.
        f32_rem(a: f32, b: f32) -> [f32; 2] over pairs_where(&F16, &F16, |_, b| b != 0.0) => {
            [a % b, (a * 3.0) % -b]
        }
        /// Every compound assignment on `f32`.
        f32_compound(a: f32, b: f32) -> [f32; 4] over pairs_where(&F16, &F16, |_, b| b != 0.0), tol ulp(3) => {
            let mut acc = a;
            acc += b;
            let s1 = acc;
            acc -= 0.25;
            acc *= b;
            let s2 = acc;
            acc /= b;
            let s3 = acc;
            acc %= 2.0;
            [s1, s2, s3, acc]
        }
        /// `+ - *` and negation on `i32` (no overflow for these inputs).
        i32_add_sub_mul(a: i32, b: i32) -> [i32; 5] over pairs(&I16, &I16) => {
            [a + b, a - b, a * b, -a, a * -3 + b]
        }
        /// `wrapping_*` over the whole range, edges included.
        i32_wrapping(a: i32, b: i32) -> [i32; 3] over pairs(&I32_EDGES, &I32_EDGES) => {
            [a.wrapping_add(b), a.wrapping_sub(b), a.wrapping_mul(b)]
        }
        /// `/` truncates towards zero and `%` takes the dividend's sign, as in
        /// Rust (not division by zero nor `i32::MIN / -1`: Rust panics).
        i32_div_rem(a: i32, b: i32) -> [i32; 2]
            over pairs_where(&i64_grid(), &[-1, 3, -7, 8, i32::MIN], |a, b| !(a == i32::MIN && b == -1)) => {
            [a / b, a % b]
        }
        /// Every compound assignment on `i32`.
        i32_compound(a: i32, b: i32) -> [i32; 5] over pairs_where(&I16, &I16, |_, b| b != 0) => {
            let mut k = a;
            k += b;
            let s1 = k;
            k -= 3;
            k *= 2;
            let s2 = k;
            k /= b;
            let s3 = k;
            k %= 5;
            [s1, s2, s3, k, -k]
        }
        /// `+ *` and a subtraction that cannot underflow on `u32`.
        u32_add_sub_mul(a: u32, b: u32) -> [u32; 3] over pairs(&U16, &U16) => {
            [a + b, a * b, a.max(b) - a.min(b)]
        }
        /// `wrapping_*` over the whole range.
        u32_wrapping(a: u32, b: u32) -> [u32; 3] over pairs(&U32_EDGES, &U32_EDGES) => {
            [a.wrapping_add(b), a.wrapping_sub(b), a.wrapping_mul(b)]
        }
        /// Unsigned `/` and `%` over the whole range.
        u32_div_rem(a: u32, b: u32) -> [u32; 2] over pairs(&u64_grid(), &[1, 3, 10, 0x8000_0000]) => {
            [a / b, a % b]
        }
        /// Every compound assignment on `u32`.
        u32_compound(a: u32, b: u32) -> [u32; 4] over pairs_where(&U16, &U16, |_, b| b != 0) => {
            let mut w = a;
            w += b;
            w *= 2;
            let s1 = w;
            w -= b;
            w /= b;
            let s2 = w;
            w %= 7;
            [s1, s2, w, w + 1]
        }
        /// Unsuffixed literals take their type from their use: `u32` next to
        /// a `u32`, `i32` by default, `f32` for float literals.
        literal_typing(a: u32, b: i32) -> [i32; 4] over pairs(&U16, &I16) => {
            let three = 3;
            let unsigned = a * 2 + 1;
            let signed = three * b - 7;
            let float = 2.5 * 2.0;
            [unsigned as i32, signed, float as i32, (unsigned % 4) as i32 - 2]
        }
    }
}

// ---------------------------------------------------------------------------
// Comparison and logic
// ---------------------------------------------------------------------------

/// A test with a side effect: counts its calls, so a skipped call shows.
#[rt_function]
pub fn counted(calls: &mut u32, result: bool) -> bool {
    *calls += 1;
    result
}

differential! {
    /// `== != < <= > >=` on every scalar type and on vectors, `&& || !`
    /// (short-circuiting), and the eager `& | ^` on `bool`.
    fn comparison_and_logic {
        /// Float comparisons (`-0.0 == 0.0`).
        f32_compare(a: f32, b: f32) -> [bool; 6] over pairs(&F16, &F16) => {
            [a < b, a <= b, a > b, a >= b, a == b, a != b]
        }
        /// Signed comparisons over the whole range.
        i32_compare(a: i32, b: i32) -> [bool; 6] over pairs(&I32_EDGES, &I32_EDGES) => {
            [a < b, a <= b, a > b, a >= b, a == b, a != b]
        }
        /// Unsigned comparisons over the whole range (`0x8000_0000 > 1`).
        u32_compare(a: u32, b: u32) -> [bool; 6] over pairs(&U32_EDGES, &U32_EDGES) => {
            [a < b, a <= b, a > b, a >= b, a == b, a != b]
        }
        /// Boolean operators on every combination of three bools.
        bool_logic(p: bool, q: bool, r: bool) -> [bool; 10]
            over triples(&[false, true], &[false, true], &[false, true]) => {
            [p && q, p || q, !p, p & q, p | q, p ^ q, p == q, p != q, p && !q || r, !(p || q) & (r ^ p)]
        }
        /// `&&` and `||` skip their right side, also when it calls a helper
        /// with a side effect; `&` and `|` do not.
        short_circuit(a: i32, b: i32) -> [u32; 6] over pairs(&I16, &I16) => {
            let mut calls = 0u32;
            let both = a > 0 && counted(&mut calls, b > 0);
            let after_and = calls;
            let either = a > 0 || counted(&mut calls, b > 0);
            let after_or = calls;
            let eager = (a > 0) & counted(&mut calls, b < 0) | counted(&mut calls, a == b);
            [both as u32, after_and, either as u32, after_or, eager as u32, calls]
        }
        /// `==` on vectors is true when all components are, `!=` when any
        /// differs.
        vector_equality(a: i32, b: i32) -> [bool; 6]
            over pairs(&[0, 1, -1, 2, 5, -7, 8, 100], &[0, 1, -1, 2, 5, -7, 8, 100]) => {
            let u = vec3(a as f32, 1.0, b as f32);
            let v = vec3(b as f32, 1.0, a as f32);
            let iu = ivec2(a, b);
            let uu = uvec4(a as u32, 3, b as u32, 4);
            [
                u == v, u != v, u.xy() == v.xy(), iu == ivec2(b, a), iu != IVec2::ZERO,
                uu == uvec4(b as u32, 3, a as u32, 4),
            ]
        }
    }
}

// ---------------------------------------------------------------------------
// Bits and shifts
// ---------------------------------------------------------------------------

/// The PCG hash (Jarzynski and Olano, "Hash Functions for GPU Rendering").
#[rt_function]
pub fn pcg_hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747796405).wrapping_add(2891336453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277803737);
    (word >> 22) ^ word
}

differential! {
    /// `& | ^ !`, shifts (arithmetic `>>` on `i32`), compound bit assignment,
    /// bit counting and hashes.
    fn bits_and_shifts {
        /// Bit operators on `u32`.
        u32_bitops(a: u32, b: u32) -> [u32; 5] over pairs(&U32_EDGES, &U32_EDGES) => {
            [a & b, a | b, a ^ b, !a, !(a & b) ^ (a | !b)]
        }
        /// Bit operators on `i32`.
        i32_bitops(a: i32, b: i32) -> [i32; 5] over pairs(&I32_EDGES, &I32_EDGES) => {
            [a & b, a | b, a ^ b, !a, !(a & b) ^ (a | !b)]
        }
        /// `u32` shifts by `u32` and `i32` amounts from 0 to 31.
        u32_shifts(a: u32, s: u32) -> [u32; 5] over pairs(&U32_EDGES[..8], &shifts()) => {
            let si = s as i32;
            [a << s, a >> s, a << si, a >> si, (a << s) >> s]
        }
        /// `i32` shifts: `>>` is arithmetic (copies the sign bit).
        i32_shifts(a: i32, s: u32) -> [i32; 5] over pairs(&I32_EDGES[..8], &shifts()) => {
            let si = s as i32;
            [a << s, a >> s, a << si, a >> si, (a << s) >> s]
        }
        /// Shifts by literals, and literals shifted.
        literal_shifts(a: u32, b: i32) -> [u32; 6] over pairs(&U32_EDGES, &I32_EDGES) => {
            [a << 3, a >> 31, (b >> 4) as u32, (b << 1u32) as u32, 1 << (a % 32), (-16 >> (a % 32)) as u32]
        }
        /// Every compound bit assignment.
        compound_bits(a: u32, b: i32) -> [u32; 4] over pairs(&U32_EDGES, &I32_EDGES) => {
            let mut w = a;
            w &= 0xffff_00f0;
            w |= 1 << 31;
            w ^= b as u32;
            w <<= 3;
            w >>= 1u32;
            w <<= (b & 7) as u32;
            let mut s = b;
            s >>= 2;
            s <<= a % 8;
            s |= -16;
            s &= !(1 << 3);
            s ^= 0x55;
            s >>= (a % 5) as i32;
            [w, s as u32, !w, (!s) as u32]
        }
        /// Bit counting on `u32`.
        u32_bit_counts(a: u32) -> [u32; 4] over one(&u64_grid()) => {
            [a.count_ones(), a.leading_zeros(), a.trailing_zeros(), a.reverse_bits()]
        }
        /// Bit counting on `i32`.
        i32_bit_counts(a: i32) -> [i32; 4] over one(&i64_grid()) => {
            [a.count_ones() as i32, a.leading_zeros() as i32, a.trailing_zeros() as i32, a.reverse_bits()]
        }
        /// `is_multiple_of` (`n.is_multiple_of(0)` is `n == 0`).
        is_multiple_of(a: u32, b: u32) -> [bool; 2] over pairs(&U16, &[0, 1, 2, 3, 7, 8, 255, 65535]) => {
            [a.is_multiple_of(b), (a * 3).is_multiple_of(b + 1)]
        }
        /// Hashes: PCG and xorshift mix multiplication, shifts and xor.
        hashes(a: u32) -> [u32; 3] over one(&u64_grid()) => {
            let mut x = a | 1;
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            [pcg_hash(a), x, pcg_hash(pcg_hash(a) ^ 0x9e37_79b9)]
        }
        /// Bit operators and shifts on integer vectors, by scalars and by
        /// vectors of either signedness.
        vector_bits(a: UVec3, b: IVec3) -> [UVec3; 6] over pairs(&uvec3s(16, u32::MAX, 3), &ivec3s(16, 1 << 30, 5)) => {
            let amounts = uvec3(1, 7, 31);
            let mut w = a & b.as_uvec3() | uvec3(1, 2, 4) ^ !a;
            w <<= 2;
            w = w >> ivec3(3, 0, 1);
            w &= 0xffff;
            w |= UVec3::X;
            let signed = (b >> 1u32) << uvec3(0, 1, 2);
            [a << amounts, a >> amounts, (b >> amounts).as_uvec3(), w, signed.as_uvec3(), (b ^ -1).as_uvec3()]
        }
    }
}

// ---------------------------------------------------------------------------
// Casts
// ---------------------------------------------------------------------------

/// Floats whose integer part fits in 32 bits, for casts through `usize`.
fn f32_in_u32_range() -> Vec<f32> {
    f64_grid().into_iter().filter(|x| x.abs() < 4.0e9).collect()
}

differential! {
    /// Every `as` cast Rust allows among `f32`, `i32`, `u32`, `usize` and
    /// `bool`.
    fn casts {
        /// `f32 as i32` truncates towards zero and saturates out of range
        /// (WGSL's `i32(x)` clamps to 2147483520, the largest float below
        /// 2^31; the compiler selects `i32::MAX` from 2^31 up).
        f32_to_i32(x: f32) -> [i32; 2] over one(&f64_grid()) => {
            [x as i32, (x * 0.5) as i32]
        }
        /// `f32 as u32` truncates and saturates (negative values give 0;
        /// WGSL's `u32(x)` tops out at 4294967040).
        f32_to_u32(x: f32) -> [u32; 2] over one(&f64_grid()) => {
            [x as u32, (-x) as u32]
        }
        /// `f32 as usize` (read back through `u32`), for values that fit.
        f32_to_usize(x: f32) -> [u32; 1] over one(&f32_in_u32_range()) => {
            [(x as usize) as u32]
        }
        /// `f32 as f32` is the identity.
        f32_to_f32(x: f32) -> [f32; 1] over one(&f64_grid()) => {
            [x as f32]
        }
        /// `i32 as f32` rounds to nearest, ties to even (2^24 + 1).
        i32_to_f32(a: i32) -> [f32; 2] over one(&i64_grid()) => {
            [a as f32, (a / 3) as f32]
        }
        /// `i32 as u32` and `u32 as i32` keep the bits; `i32 as i32`.
        i32_u32_bits(a: i32) -> [i32; 3] over one(&i64_grid()) => {
            let u = a as u32;
            [(u >> 1) as i32, u as i32, a as i32]
        }
        /// `i32 as usize` keeps the bits on the way back to 32 bits; as an
        /// array index it must be non-negative.
        i32_to_usize(a: i32) -> [u32; 2] over one(&i64_grid()) => {
            let table = [10u32, 20, 30, 40];
            [(a as usize) as u32, table[(a & 3) as usize]]
        }
        /// `u32 as f32` rounds to nearest (values above 2^24 included).
        u32_to_f32(a: u32) -> [f32; 2] over one(&u64_grid()) => {
            [a as f32, (a >> 16) as f32]
        }
        /// `u32 as u32`, `u32 as usize` and back, `u32 as i32`.
        u32_casts(a: u32) -> [u32; 3] over one(&u64_grid()) => {
            [a as u32, (a as usize) as u32, (a as i32 >> 1) as u32]
        }
        /// `usize` to every type, from values that fit in 32 bits.
        usize_casts(a: u32) -> [f32; 4] over one(&u64_grid()) => {
            let z = a as usize;
            let back = z as usize;
            [z as f32, (z as i32) as f32, (z as u32 % 1000) as f32, (back % 7) as f32]
        }
        /// `bool` to every integer type (and `bool as bool`).
        bool_casts(p: bool, a: u32) -> [u32; 4] over pairs(&[false, true], &U16) => {
            let weights = [a, a + 1];
            [p as u32 + a, (p as i32 - 1) as u32, weights[p as usize], (p as bool) as u32]
        }
    }
}
