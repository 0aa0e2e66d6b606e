//! Generic structs, one WGSL struct per instance (`rt_Pair__f32`,
//! `rt_Pair__Vec3`) and the methods of their generic `#[rt_impl]` block
//! one function per instance: `Pair<f32>` and `Pair<Vec3>` in one program,
//! built by literal (the arguments inferred from the fields, the wanted
//! type or a turbofish) and by associated function, a generic method of
//! the generic block, a generic struct holding another, instances in a
//! tuple, an `Option` and an array, a generic helper and a plain one
//! taking one; a generic tuple struct built by call and destructured;
//! `Default` at an instance; operator impls and an `#[rt_trait]` impl of
//! the generic struct, called as operators, by name and through a helper
//! bounded by the trait.

use super::*;
use core::ops::{Add, Mul, Neg};

/// Two values of one type.
#[rt_struct(impl, impl Add, impl Mul<f32>, impl Neg, impl Scale)]
pub struct Pair<T> {
    pub a: T,
    pub b: T,
}

#[rt_impl]
impl<T: Copy + Add<Output = T> + Mul<f32, Output = T>> Pair<T> {
    /// A constant that names no parameter: one for every instance.
    pub const HALF: f32 = 0.5;

    pub fn new(a: T, b: T) -> Self {
        Pair { a, b }
    }

    pub fn sum(&self) -> T {
        self.a + self.b
    }

    /// `b` first.
    pub fn swapped(self) -> Self {
        Self { a: self.b, b: self.a }
    }

    /// Both values scaled, in place.
    pub fn scale(&mut self, s: f32) {
        self.a = self.a * (s * Self::HALF * 2.0);
        self.b = self.b * s;
    }

    /// A generic method of the generic block: `a` beside a value of any
    /// type.
    pub fn first_with<U: Copy>(&self, u: U) -> (T, U) {
        (self.a, u)
    }
}

#[rt_impl]
impl<T: Copy + Add<Output = T>> Add for Pair<T> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Pair { a: self.a + o.a, b: self.b + o.b }
    }
}

#[rt_impl]
impl<T: Copy + Mul<f32, Output = T>> Mul<f32> for Pair<T> {
    type Output = Pair<T>;
    fn mul(self, k: f32) -> Pair<T> {
        Pair { a: self.a * k, b: self.b * k }
    }
}

#[rt_impl]
impl<T: Copy + Neg<Output = T>> Neg for Pair<T> {
    type Output = Self;
    fn neg(self) -> Self {
        Pair { a: -self.b, b: -self.a }
    }
}

/// Scaling by a factor, with a default method calling the required one.
#[rt_trait]
pub trait Scale {
    /// A default constant, which the generic impl keeps.
    const FACTOR: f32 = 2.0;
    fn scaled(&self, k: f32) -> Self;
    fn twice(&self) -> Self
    where
        Self: Sized,
    {
        self.scaled(Self::FACTOR)
    }
}

#[rt_impl]
impl<T: Copy + Mul<f32, Output = T>> Scale for Pair<T> {
    fn scaled(&self, k: f32) -> Self {
        Pair { a: self.a * k, b: self.b * (k + 1.0) }
    }
}

/// A generic helper bounded by the trait.
#[rt_function]
pub fn halve<S: Scale>(s: S) -> S {
    s.scaled(0.5)
}

/// A generic struct holding an instance of another.
#[rt_struct]
pub struct Weighted<T> {
    pub pair: Pair<T>,
    pub w: f32,
}

/// A generic helper taking an instance: the weighted sum.
#[rt_function]
pub fn weighted_sum<T: Copy + Add<Output = T> + Mul<f32, Output = T>>(p: Weighted<T>) -> T {
    p.pair.sum() * p.w
}

/// A plain helper taking an instance: its unit and the program's declare
/// the same `rt_Pair__f32`, which the linker keeps once.
#[rt_function]
pub fn pair_gap(p: Pair<f32>) -> f32 {
    p.b - p.a
}

/// Two values of one type, unnamed.
#[rt_struct(impl)]
pub struct Two<T>(pub T, pub T);

#[rt_impl]
impl<T: Copy + Add<Output = T>> Two<T> {
    pub fn sum(&self) -> T {
        self.0 + self.1
    }
}

/// A generic helper destructuring a generic tuple struct.
#[rt_function]
pub fn swap_two<T: Copy>(t: Two<T>) -> Two<T> {
    let Two(p, q) = t;
    Two(q, p)
}

differential! {
    /// `Pair<f32>` and `Pair<Vec3>` together, and the ways to build and use them.
    fn generic_struct_programs {
        /// Literals, associated functions, methods, nesting and containers.
        pairs_at_two_types(a: f32, b: f32) -> [f32; 8] over pairs(&spread(7, -3.0, 3.0), &spread(5, -1.0, 2.0)), tol CHAINED => {
            let p = Pair { a, b };
            let v: Pair<Vec3> = Pair::new(Vec3::new(a, b, 1.0), Vec3::splat(b));
            let mut q = Pair::<f32> { a: b, b: 2.0 }.swapped();
            q.scale(a);
            let w = Weighted { pair: v, w: 0.5 };
            let ws = weighted_sum(w);
            let t = p.first_with(v.b);
            let o: Option<Pair<f32>> = if a > 0.0 { Some(p) } else { None };
            let arr = [p, q];
            [p.sum(), v.sum().x + v.sum().y + v.sum().z, q.a - q.b, ws.x + ws.z, t.0 + t.1.y + pair_gap(q), o.map_or(-1.0, |x| x.b), arr[1].sum(), weighted_sum(Weighted { pair: p, w: 2.0 })]
        }
        /// A generic tuple struct built by call (inferred, by turbofish, at
        /// the wanted type), read by index, destructured, through a helper.
        tuple_pairs(a: f32, b: f32) -> [f32; 4] over pairs(&spread(7, -3.0, 3.0), &spread(5, -1.0, 2.0)), tol CHAINED => {
            let t = Two(a, b);
            let v = Two::<Vec3>(Vec3::splat(a), Vec3::new(b, a, 1.0));
            let n: Two<u32> = Two(3, 4);
            let Two(p, q) = swap_two(t);
            [t.0 - t.1 * 2.0, v.sum().y + v.1.z, (n.0 * n.1) as f32 + p, q * swap_two(v).0.x]
        }
        /// `Default` at an instance named or wanted, alone and as the base
        /// of a literal.
        defaults(a: f32, b: f32) -> [f32; 4] over pairs(&spread(5, -3.0, 3.0), &spread(3, -1.0, 2.0)), tol CHAINED => {
            let z: Pair<Vec3> = Pair::default();
            let y = Pair::<f32>::default();
            let p = Pair { a, ..Default::default() };
            let q: Pair<f32> = Pair { b, ..Pair::default() };
            let t = Two::<u32>::default();
            [z.a.x + z.b.y + y.a + y.b, p.a + p.b * 2.0, q.a - q.b, (t.0 + t.1) as f32 + a]
        }
        /// Operators (`+`, `* f32`, unary `-`, and `add` by name) and the
        /// trait's methods (one a default) on `Pair<f32>` and `Pair<Vec3>`.
        operators_and_traits(a: f32, b: f32) -> [f32; 6] over pairs(&spread(7, -3.0, 3.0), &spread(5, -1.0, 2.0)), tol CHAINED => {
            let p = Pair { a, b };
            let v = Pair::new(Vec3::new(a, b, 1.0), Vec3::splat(b));
            let q = -(p + p * 2.0);
            let w = v.add(v).twice();
            let h = halve(p).scaled(3.0);
            let k = Pair::<f32>::HALF + Pair::<Vec3>::FACTOR;
            [q.a, q.b, w.sum().x + w.b.z, h.a + h.b * k, halve(v).a.y + (-v).b.x, (p * a).twice().sum()]
        }
    }
}
