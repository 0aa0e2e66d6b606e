//! Patterns in `let` positions: `if let`, `while let` and `let ... else`
//! over integers, ranges, `|`, enums, tuples and bindings, as values, in
//! loops and in helpers that return early.

use super::enums::{Shape, shape_of};
use super::*;

/// `let ... else` with a tuple pattern and a range inside it: the bound
/// name, or the early return.
#[rt_function]
pub fn small_second(t: (u32, u32)) -> u32 {
    let (a, 0..=9) = t else {
        return 1000;
    };
    let (mut b, 0..=5) = (a, t.1 % 6) else { return 0 };
    b += 1;
    a + b + t.1
}

/// `let ... else` binding nothing (an enum variant) and one name.
#[rt_function]
pub fn torus_only(s: Shape, r: f32) -> f32 {
    let Shape::Torus = s else {
        return -1.0;
    };
    let k @ 0..=2 = (r * 2.0) as u32 else { return -2.0 };
    r * 3.0 + k as f32
}

differential! {
    /// `if let`, `while let` and `let ... else` lowered as the `match` they mean.
    fn let_patterns {
        /// `if let` as a value and a statement, chained with `else if let`;
        /// tuples with `|` and bindings; enums.
        if_lets(n: u32, x: i32) -> [i32; 4] over pairs(&[0, 1, 2, 5, 9, 10, 42, u32::MAX], &[-3, -1, 0, 1, 2, 7]) => {
            let a = if let 0 = n { 1 } else if let 1..=9 = n { 2 } else if let k @ 10..=50 = n { 3 + k as i32 } else { 4 };
            let mut b = 0;
            if let (0 | 1, k) = (n, x) {
                b = k * 10;
            } else if let (_, -1 | 7) = (n, x) {
                b = -5;
            }
            let c = if let Shape::Cube | Shape::Torus = shape_of(n) { 7 } else { 8 };
            let d = if let (q, 1..=3) = (x, n % 4) { q * 2 } else { 0 };
            [a, b, c, d]
        }
        /// `while let` over a range pattern and a tuple, with `break` and
        /// `continue`; `let ... else` in a loop body leaving with `continue`.
        while_lets(n: u32) -> [u32; 3] over one(&[0, 1, 2, 3, 7, 8, 15, 100, u32::MAX]) => {
            let mut i = n % 8;
            let mut sum = 0;
            while let 1..=7 = i {
                sum += i;
                i -= 1;
            }
            let mut state = (n % 5, 0u32);
            'walk: while let (1..=4, steps) = state {
                state = (state.0 - 1, steps + 1);
                if steps > 10 {
                    break 'walk;
                }
            }
            let mut odd = 0;
            for k in 0..n % 9 {
                let 1 = k % 2 else { continue };
                odd += k;
            }
            [sum, state.1, odd]
        }
        /// `let ... else` in helpers: tuples, ranges, enums, `@` bindings.
        let_elses(n: u32, r: f32) -> [f32; 2] over pairs(&[0, 3, 9, 10, 11, 20, 35], &[0.0, 0.25, 0.5, 1.0, 1.75]) => {
            [small_second((n, n % 12)) as f32, torus_only(shape_of(n), r)]
        }
    }
}
