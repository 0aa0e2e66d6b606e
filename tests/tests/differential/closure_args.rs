//! Closures given to generic helpers (`F: Fn(..)` and `impl Fn(..)`
//! parameters), inlined where they are called: a helper whose local has
//! the name of a variable the closure captures, a closure that writes what
//! it captures (`FnMut`), one helper handing a closure to another, and a
//! helper declared in the program's body.

use super::*;

/// Calls `f` twice; its own `k` is not the caller's.
#[rt_function]
pub fn apply_twice<F: Fn(f32) -> f32>(f: F, x: f32) -> f32 {
    let k = f(x);
    f(k) - k
}

/// Calls `f` on each element.
#[rt_function]
pub fn each(mut f: impl FnMut(f32), xs: [f32; 3]) {
    for v in xs {
        f(v);
    }
}

/// Hands a closure of its own to `apply_twice`.
#[rt_function]
pub fn scaled<F: Fn(f32) -> f32>(f: F, s: f32, x: f32) -> f32 {
    apply_twice(|v: f32| f(v) * s, x)
}

differential! {
    /// Closures given to helpers.
    fn closure_args {
        /// Captures, a written capture, nesting, a helper in the body.
        calls(a: f32, n: u32) -> [f32; 4] over pairs(&[0.5, -1.25, 3.0], &[0, 1, 2]), tol CHAINED => {
            let k = a + 1.0;
            let p = apply_twice(|v: f32| v * k + n as f32, a);
            let mut sum = 0.0;
            each(|v| sum += v * k, [a, 1.0, n as f32]);
            let q = scaled(|v: f32| v - k, 0.5, a);
            fn pick<G: Fn(u32) -> bool>(g: G, m: u32) -> f32 {
                if g(m) { 1.0 } else { -1.0 }
            }
            [p, sum, q, pick(|m| m % 2 == 0, n)]
        }
    }
}
