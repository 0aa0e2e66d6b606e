//! `Option<T>`: built with `Some`/`None`, returned from and passed to
//! helpers, matched, destructured with `if let`, `while let` and
//! `let ... else`, and through its methods with and without closures, at
//! scalars, vectors, tuples, arrays and structs.

// The forms under test are spelled out: a search loop, a closure for a
// constant default, a `None` literal's default, a comparison with `None`.
#![allow(
    clippy::manual_find,
    clippy::unnecessary_lazy_evaluations,
    clippy::unnecessary_literal_unwrap,
    clippy::partialeq_to_none
)]

use super::*;

/// The first index whose element exceeds `x`, if any: `Option` as a result.
#[rt_function]
pub fn first_above(arr: [f32; 4], x: f32) -> Option<u32> {
    for i in 0..4u32 {
        if arr[i as usize] > x {
            return Some(i);
        }
    }
    None
}

/// `Option` as a parameter and a result, through a closure method.
#[rt_function]
pub fn halved(o: Option<f32>) -> Option<f32> {
    o.map(|v| v * 0.5)
}

/// A struct carried in an `Option`.
#[rt_struct]
pub struct Hit {
    pub t: f32,
    pub id: u32,
}

/// The nearer of two hits, either maybe missing.
#[rt_function]
pub fn nearer(a: Option<Hit>, b: Option<Hit>) -> Option<Hit> {
    match (a, b) {
        (Some(x), Some(y)) => {
            if y.t < x.t {
                Some(y)
            } else {
                Some(x)
            }
        }
        (Some(x), None) => Some(x),
        (None, y) => y,
    }
}

/// `let ... else` on an `Option` in a helper.
#[rt_function]
pub fn id_or_sentinel(h: Option<Hit>) -> u32 {
    let Some(hit) = h else {
        return 99;
    };
    hit.id
}

/// A `None` local typed by the helper's result.
#[rt_function]
pub fn none_unless(x: u32) -> Option<u32> {
    let o = None;
    if x > 2 {
        return Some(x);
    }
    o
}

differential! {
    /// Option values and their methods.
    fn options {
        /// Built, matched with guards and ranges, `if let`, methods
        /// without closures.
        values(n: u32, x: f32) -> [f32; 4] over pairs(&[0, 1, 2, 3, 7, 10, 4000000000], &[-1.5, 0.0, 0.5, 1.0, 2.5, 4.0]) => {
            let arr = [0.25, 1.0, 2.0, 3.5];
            let found = first_above(arr, x);
            let a = match found {
                Some(0) => 10.0,
                Some(k @ 1..=2) => k as f32,
                Some(k) if k > 2 => 5.0,
                Some(_) => 6.0,
                None => -1.0,
            };
            let small = if n < 5 { Some(n) } else { None };
            let mut b = 0.0;
            if let Some(k) = small {
                b = k as f32 + small.is_some() as u32 as f32;
            } else if small.is_none() {
                b = -2.0;
            }
            let none: Option<f32> = None;
            let c = none.or(Some(x)).unwrap_or(7.0) + none.unwrap_or_default() + Some(x).xor(none).unwrap_or(1.0);
            let d = found.map(|i| arr[i as usize]).unwrap_or(x);
            [a, b, c, d]
        }
        /// Closure methods, `while let`, `let ... else` in a loop, vectors,
        /// tuples and arrays inside.
        closures(n: u32, x: f32) -> [f32; 4] over pairs(&[0, 1, 2, 5, 9, 12], &[-2.0, 0.0, 0.75, 3.0]) => {
            let o = Some(n).filter(|k| *k % 3 != 0).and_then(|k| if k < 9 { Some(k as f32) } else { None });
            let a = o.map_or(-1.0, |v| v * 2.0) + halved(o).unwrap_or_else(|| 0.25);
            let mut left = Some(n % 6);
            let mut sum = 0;
            while let Some(k) = left {
                sum += k;
                left = if k > 0 { Some(k - 1) } else { None };
            }
            let mut count = 0.0;
            for i in 0..4 {
                let Some(j) = first_above([0.5, 1.5, 2.5, 3.5], x + i as f32) else { continue };
                count += j as f32;
            }
            let pair: Option<(u32, Vec3)> = if x > 0.0 { Some((n, Vec3::new(x, 1.0, 2.0))) } else { None };
            let p = match pair {
                Some((k, v)) if k > 1 => v.x + v.z,
                Some((_, v)) => v.y,
                None => 0.0,
            };
            let arr: Option<[f32; 3]> = Some([x, 2.0, 3.0]);
            let q = arr.is_some_and(|a| a[0] > 0.5) as u32 as f32 + Some(x).is_none_or(|y| y > 1.0) as u32 as f32;
            [a, sum as f32 + count, p, q]
        }
        /// Structs in options, through helpers.
        structs(n: u32, x: f32) -> [u32; 2] over pairs(&[0, 1, 2, 3], &[0.0, 1.0, 2.0]) => {
            let a = if n % 2 == 0 { Some(Hit { t: x, id: n }) } else { None };
            let b = if n > 1 { Some(Hit { t: 1.0, id: 50 + n }) } else { None };
            let near = nearer(a, b);
            [id_or_sentinel(near), near.map_or(0, |h| h.id + 1)]
        }
        /// The reductions of iterator chains that return an `Option`.
        reductions(n: u32, x: f32) -> [f32; 4] over pairs(&[0, 1, 2, 5, 9, 14], &[-1.0, 0.5, 1.5, 2.5, 5.0]) => {
            let arr = [x, 1.0, 2.0, 3.0];
            let a = arr.iter().position(|v| *v > 1.5).map_or(-1.0, |i| i as f32);
            let b = [3u32, n, 2].iter().min().copied().unwrap_or(0) as f32
                + (0..n).map(|i| i * 3 % 7).max().unwrap_or(100) as f32;
            let c = arr.iter().find(|v| **v > 1.5).copied().unwrap_or(-2.0);
            let d = (0..n).filter(|i| i % 2 == 1).position(|i| i > 4).map_or(-1.0, |p| p as f32);
            [a, b, c, d]
        }
        /// A `None` in an `if`'s first branch, typed by the branch after
        /// it (an `else`, an `else if` chain).
        none_first(n: u32, x: f32) -> [u32; 2] over pairs(&[0, 1, 2, 3, 6], &[0.0, 1.0]) => {
            let a = if n > 2 { None } else { Some(n * 2) };
            let b = if x > 0.5 { None } else if n == 1 { Some(7) } else { Some(n + 100) };
            [a.unwrap_or(99), b.unwrap_or(98)]
        }
        /// `let mut o = None;` typed by a later assignment, as rustc infers
        /// it: in a loop (the value a local of the loop's body), in an
        /// `if`, of an integer literal (`u32` by its use), of a struct.
        none_assigned_later(n: u32, x: f32) -> [f32; 4] over pairs(&[0, 1, 2, 5, 9], &[-1.0, 0.5, 2.5]) => {
            let arr = [x, 1.0, 2.0, 3.0];
            let mut best = None;
            for i in 0..4 {
                let d = arr[i] * 2.0 - n as f32;
                let nearer = match best {
                    Some(b) => d < b,
                    None => true,
                };
                if d > 0.0 && nearer {
                    best = Some(d);
                }
            }
            let mut count = None;
            if n > 1 {
                count = Some(3);
            }
            let mut hit = None;
            if x > 0.0 {
                hit = Some(Hit { t: x, id: n });
            }
            [best.unwrap_or(-1.0), count.map_or(0, |c| c + n) as f32, hit.map_or(-5.0, |h| h.t), hit.map_or(0.0, |h| h.id as f32)]
        }
        /// `==` and `!=` of `Option`s: with `None`, with `Some(x)`, two
        /// variables, a nested `Option`.
        equality(n: u32, x: f32) -> [u32; 5] over pairs(&[0, 1, 2, 3, 6], &[0.0, 1.0, 2.0]) => {
            let o = if n % 3 != 0 { Some(n) } else { None };
            let p = if x > 0.5 { Some(n) } else { None };
            let q = if n > 2 { Some(Some(x)) } else { Some(None) };
            [
                (o == None) as u32,
                (o != None) as u32 + 2 * (o == Some(1)) as u32,
                (o == p) as u32 + 2 * (p != o) as u32,
                (q == Some(None)) as u32 + 2 * (q == Some(Some(2.0))) as u32,
                (Some(x) != Some(1.0)) as u32,
            ]
        }
        /// `let o = None;` typed by a later use: passed to a parameter,
        /// compared with an `Option`, given a value by `unwrap_or`, the
        /// result of a helper.
        none_typed_by_use(n: u32, x: f32) -> [f32; 4] over pairs(&[0, 1, 2, 5, 9], &[-1.0, 0.5, 2.5]) => {
            let a = None;
            let h = nearer(a, Some(Hit { t: x, id: n }));
            let b = None;
            let same = b == Some(n);
            let mut c = None;
            let k = c.unwrap_or(x);
            if n > 1 {
                c = Some(x * 2.0);
            }
            [h.map_or(-1.0, |h| h.t), same as u32 as f32 + none_unless(n).unwrap_or(7) as f32, k, c.unwrap_or(0.5)]
        }
    }
}
