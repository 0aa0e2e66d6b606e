//! Control flow: `if`, loops, `match`, helpers with `&mut` parameters.

use super::*;

// ---------------------------------------------------------------------------
// Control flow
// ---------------------------------------------------------------------------

/// Buckets a value: an early return, then an `else if` chain as the tail.
#[rt_function]
pub fn bucket(v: f32) -> i32 {
    if v < 0.0 {
        return -1;
    }
    if v == 0.0 {
        0
    } else if v < 1.0 {
        1
    } else if v < 10.0 {
        2
    } else {
        3
    }
}

/// The first `i` in `0..n` with `i * i >= target`: a return from inside a
/// loop.
#[rt_function]
pub fn first_square_at_least(n: u32, target: u32) -> u32 {
    for i in 0..n {
        if i * i >= target {
            return i;
        }
    }
    n
}

/// Pops the lowest set bit of `mask` into `bit`; false when none is left.
#[rt_function]
pub fn pop_bit(mask: &mut u32, bit: &mut u32) -> bool {
    if *mask == 0 {
        return false;
    }
    *bit = mask.trailing_zeros();
    *mask &= *mask - 1;
    true
}

differential! {
    /// `if`/`else` statements and expressions, `else if` chains, `while`,
    /// `loop`/`break`, `for` over `a..b` and `a..=b`, `continue`, early
    /// returns, `match` on integers, blocks and shadowing.
    fn control_flow {
        /// `if` as an expression and as a statement, nested.
        if_else(x: f32) -> [f32; 3] over one(&f64_grid()) => {
            let sign = if x < 0.0 { -1.0 } else if x > 0.0 { 1.0 } else { 0.0 };
            let mut y = x;
            if y > 100.0 {
                y = 100.0;
            } else {
                if y < -100.0 {
                    y = -100.0;
                }
            }
            let z = if sign > 0.0 { if y > 50.0 { 2.0 } else { 1.0 } } else { 0.5 };
            [sign, y, z]
        }
        /// An `else if` chain with an early `return` before it, in a helper.
        else_if_chain(x: f32) -> [i32; 2] over one(&f64_grid()) => {
            [bucket(x), bucket(x * 0.01 - 0.5)]
        }
        /// `while`: Collatz steps.
        while_loop(n: u32) -> [u32; 2] over one(&(1..=64).collect::<Vec<u32>>()) => {
            let mut k = n;
            let mut steps = 0u32;
            let mut peak = k;
            while k > 1 {
                if k % 2 == 0 {
                    k /= 2;
                } else {
                    k = 3 * k + 1;
                }
                peak = peak.max(k);
                steps += 1;
            }
            [steps, peak]
        }
        /// `loop` with `break`: Newton's iteration for a square root.
        loop_break(x: f32) -> [f32; 2] over one(&spread(64, 0.5, 1000.0)), tol ulp(8) => {
            let mut r = x;
            let mut iters = 0;
            loop {
                r = 0.5 * (r + x / r);
                iters += 1;
                if iters == 30 || (r * r - x).abs() < 1e-3 * x {
                    break;
                }
            }
            [r, iters as f32]
        }
        /// `for` over `a..b`, `a..=b`, empty ranges, ranges with computed and
        /// negative bounds, and `continue`.
        for_ranges(n: i32, m: i32) -> [i32; 5]
            over pairs(&[-3, -1, 0, 1, 2, 5, 9, 16], &[-2, 0, 1, 3, 4, 7, 8, 12]) => {
            let mut a = 0;
            for i in n..m {
                a += i;
            }
            let mut b = 0;
            for i in n..=m {
                b += i * i;
            }
            let mut c = 0;
            for i in 0..n + m {
                if i % 3 == 0 {
                    continue;
                }
                c += i;
            }
            let mut d = 0;
            for i in -5..=-2 {
                d = d * 2 + i;
            }
            let mut e = 0;
            for i in 1..4 {
                for j in i..=n {
                    if j > 6 {
                        break;
                    }
                    e += i * j;
                }
            }
            [a, b, c, d, e]
        }
        /// `for` over `u32` ranges; `while` with `continue` and a condition
        /// that calls a helper mutating state.
        loops_u32(mask: u32, n: u32) -> [u32; 3] over pairs(&u64_grid()[..32], &[0, 1, 5, 8]) => {
            let mut bits_seen = 0u32;
            let mut remaining = mask;
            let mut bit = 0u32;
            while pop_bit(&mut remaining, &mut bit) {
                if bit % 4 == 1 {
                    continue;
                }
                bits_seen += bit;
            }
            let mut sum = 0u32;
            for row in 0..3u32 {
                for col in row..=n + 1 {
                    sum += row * col;
                }
            }
            [bits_seen, sum, first_square_at_least(n * 3, mask % 50)]
        }
        /// `match` on `i32`: literal arms, `|` alternatives, negative
        /// literals, `_`, a binding catch-all, as a statement and as an
        /// expression inside arithmetic.
        match_i32(a: i32) -> [i32; 3] over one(&(-20..44).collect::<Vec<i32>>()) => {
            let kind = match a {
                0 => 100,
                1 | 2 => 200,
                -1 | -2 | -3 => 300,
                7 | 11 | 13 => 400,
                _ => 500,
            };
            let mut acc = 0;
            match a % 4 {
                0 => acc += 1,
                1 | -1 => {
                    acc -= 10;
                }
                -3 => {}
                _ => acc = 7,
            }
            let scaled = 1 + match a {
                0 => 0,
                d => 1000 / d,
            };
            [kind, acc, scaled]
        }
        /// `match` on `u32` with a binding arm.
        match_u32(a: u32) -> [u32; 2] over one(&(0..64).collect::<Vec<u32>>()) => {
            let lobe = match a % 8 {
                0 => 1,
                1 | 3 | 5 => 2,
                other => other * 10,
            };
            let r = match a {
                0 | 63 => 0,
                x => x * 2,
            };
            [lobe, r]
        }
        /// Blocks as expressions and as scopes; `let` shadowing.
        blocks_and_shadowing(x: f32) -> [f32; 3] over one(&f64_grid()) => {
            let v = x;
            let v = v * 2.0;
            let w = {
                let v = v + 1.0;
                v * 3.0
            };
            let mut u = v;
            {
                let u2 = u * 0.5;
                u = u2 - 1.0;
            }
            [v, w, u]
        }
    }
}
