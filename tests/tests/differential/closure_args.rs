//! Closures given to generic helpers (`F: Fn(..)` and `impl Fn(..)`
//! parameters), inlined where they are called: a helper whose local has
//! the name of a variable the closure captures, a closure that writes what
//! it captures (`FnMut`), one helper handing a closure to another, and a
//! helper declared in the program's body; and methods given closures:
//! `&self` and `self` methods called by name and by path, an associated
//! function, a method that hands a closure to another through `Self::`,
//! a generic struct's method.

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

/// A range of values with methods that take closures.
#[rt_struct(impl)]
pub struct Span1 {
    pub lo: f32,
    pub hi: f32,
}

#[rt_impl]
impl Span1 {
    pub const STEPS: u32 = 4;

    /// `f` at the ends and the middle, summed.
    pub fn sample<F: Fn(f32) -> f32>(&self, f: F) -> f32 {
        let mid = (self.lo + self.hi) * 0.5;
        f(self.lo) + f(mid) + f(self.hi)
    }

    /// Each end mapped by `f`.
    pub fn mapped(mut self, f: impl Fn(f32) -> f32) -> Self {
        self.lo = f(self.lo);
        self.hi = f(self.hi);
        self
    }

    /// A span from `f` at 0 and 1.
    pub fn from_fn<F: Fn(f32) -> f32>(f: F) -> Span1 {
        Span1 { lo: f(0.0), hi: f(1.0) }
    }

    /// Hands its own closure to `sample`, through `Self::`.
    pub fn sample_scaled<F: Fn(f32) -> f32>(&self, f: F, s: f32) -> f32 {
        Self::sample(self, |v: f32| f(v) * s) + Self::STEPS as f32
    }
}

/// A generic pair whose method takes a closure.
#[rt_struct(impl)]
pub struct Duo<T> {
    pub a: T,
    pub b: T,
}

#[rt_impl]
impl<T: Copy> Duo<T> {
    /// `f` of each, summed.
    pub fn total<F: Fn(T) -> f32>(&self, f: F) -> f32 {
        let first: T = self.a;
        f(first) + f(self.b)
    }
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

        /// Methods given closures: by name, by path, by value, an
        /// associated function, one through another.
        methods(a: f32, n: u32) -> [f32; 4] over pairs(&[0.5, -1.25, 3.0], &[0, 1, 2]), tol CHAINED => {
            let k = a * 2.0;
            let s = Span1 { lo: a, hi: a + n as f32 };
            let m = s.mapped(|v| v * k + 1.0);
            let t = Span1::from_fn(|x: f32| x * k - a);
            [
                s.sample(|v: f32| v * k),
                Span1::sample(&m, |v| v - k) + t.lo + t.hi,
                s.sample_scaled(|v: f32| v + k, 0.5),
                m.lo * m.hi + Duo { a: vec2(a, k), b: Vec2::ONE }.total(|v| v.x * v.y),
            ]
        }
    }
}
