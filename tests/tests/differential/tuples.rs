//! Tuples: built, returned from helpers, destructured, indexed, assigned,
//! stored in struct fields and matched element by element.

use super::*;

/// Two results at once.
#[rt_function]
pub fn div_rem(a: u32, b: u32) -> (u32, u32) {
    (a / b, a % b)
}

/// A tuple parameter, matched on its integer elements.
#[rt_function]
pub fn classify(p: (i32, i32)) -> i32 {
    match p {
        (0, 0) => 100,
        (0, y) => y * 2,
        (1, _) | (_, 1) => -7,
        (x, -1) => x,
        _ => 5,
    }
}

/// A struct with a tuple field.
#[rt_struct]
pub struct Span2 {
    pub range: (f32, f32),
    pub steps: u32,
}

differential! {
    /// Tuples as values.
    fn tuples_as_values {
        /// `(u32, u32)` from a helper, destructured; `.0`/`.1`; `mut`
        /// bindings; nested tuples; `_`.
        destructure(a: u32) -> [u32; 4] over one(&u64_grid().into_iter().filter(|&a| a < 1 << 30).collect::<Vec<_>>()) => {
            let (q, mut r) = div_rem(a, 7);
            r += 1;
            let t = div_rem(a, 10);
            let mut nested = ((q, r), t.1);
            nested.1 += 2;
            (nested.0).0 += 1;
            let ((x, _), z) = nested;
            [x, r, z, t.0]
        }
        /// `match` over a tuple of integers.
        matched(a: i32, b: i32) -> [i32; 1] over pairs(&[-2, -1, 0, 1, 2, 3], &[-1, 0, 1, 4]) => {
            [classify((a, b))]
        }
        /// Integers of tuple literals inferred from later uses (`u32` from a
        /// read, a destructured element, a nested element; `i32` where
        /// nothing decides).
        inferred(a: u32) -> [u32; 4] over one(&[0, 1, 7, 1000, 1 << 31, u32::MAX - 9]) => {
            let t = (5, 2.5);
            let x: u32 = t.0 + (a & 0xffff);
            let (p, q) = (4000000000, 3);
            let y = p ^ a;
            let n = ((1, 4294967295), 3);
            let z: u32 = (n.0).1 - (a & 0xff);
            let mut m = (3, 0.5);
            m.0 += a >> 4;
            [x, y, z, m.0 + (q * n.1 - (n.0).0) as u32 + t.1 as u32]
        }
        /// `sin_cos` and a struct field of a tuple type.
        tuple_sin_cos(x: f32) -> [f32; 3] over one(&spread(32, -3.0, 3.0)), tol ulp_or_abs(0, 2.0f32.powi(-11)) => {
            let (s, c) = x.sin_cos();
            let span = Span2 { range: (s, c), steps: 3 };
            let copy = span;
            [copy.range.0, copy.range.1, span.steps as f32]
        }
    }
}
