//! Operator traits of std implemented for user structs under `#[rt_impl]`:
//! `+ - * /` between two values and with a scalar on the right (`Mul` and
//! `Mul<f32>` side by side), `-a`, `!a`, compound assignments through
//! `AddAssign`/`MulAssign` (one whose meaning differs from `+`), and `Index`,
//! in programs, helpers, methods and a generic helper bounded by `Add`;
//! and the traits' methods called by name (`a.add(b)`, `a.neg()`).

use super::*;
use std::ops::{Add, AddAssign, BitAnd, BitOrAssign, BitXor, Div, Index, Mul, MulAssign, Neg, Not, Sub};

/// A colour with operators.
#[rt_struct(impl, impl Add, impl Sub, impl Mul, impl Mul<f32>, impl Div<f32>, impl Neg, impl AddAssign, impl MulAssign<f32>, impl Index<usize>)]
pub struct Rgb3 {
    pub r: f32,
    pub g: f32,
    pub b: f32,
}

#[rt_impl]
impl Rgb3 {
    pub fn new(r: f32, g: f32, b: f32) -> Rgb3 {
        Rgb3 { r, g, b }
    }
    /// An operator inside a method.
    pub fn doubled(&self) -> Rgb3 {
        *self + *self
    }
    /// Operators called by name on `&self`.
    pub fn halved_sum(&self, o: Rgb3) -> f32 {
        let s = self.add(o).mul(0.5);
        s.r + s.g + s.b
    }
}

#[rt_impl]
impl Add for Rgb3 {
    type Output = Rgb3;
    fn add(self, o: Rgb3) -> Rgb3 {
        Rgb3::new(self.r + o.r, self.g + o.g, self.b + o.b)
    }
}

#[rt_impl]
impl Sub for Rgb3 {
    type Output = Self;
    fn sub(self, o: Self) -> Self::Output {
        Rgb3::new(self.r - o.r, self.g - o.g, self.b - o.b)
    }
}

#[rt_impl]
impl Mul for Rgb3 {
    type Output = Rgb3;
    fn mul(self, o: Rgb3) -> Rgb3 {
        Rgb3::new(self.r * o.r, self.g * o.g, self.b * o.b)
    }
}

#[rt_impl]
impl Mul<f32> for Rgb3 {
    type Output = Rgb3;
    fn mul(self, k: f32) -> Rgb3 {
        Rgb3::new(self.r * k, self.g * k, self.b * k)
    }
}

#[rt_impl]
impl Div<f32> for Rgb3 {
    type Output = Rgb3;
    fn div(self, k: f32) -> Rgb3 {
        let k = if k == 0.0 { 1.0 } else { k };
        Rgb3::new(self.r / k, self.g / k, self.b / k)
    }
}

#[rt_impl]
impl Neg for Rgb3 {
    type Output = Rgb3;
    fn neg(self) -> Rgb3 {
        Rgb3::new(-self.r, -self.g, -self.b)
    }
}

/// Adds, and counts the addition in `b` (so `+=` is seen to be this, not `+`).
#[rt_impl]
impl AddAssign for Rgb3 {
    fn add_assign(&mut self, o: Rgb3) {
        self.r += o.r;
        self.g += o.g;
        self.b += o.b + 1.0;
    }
}

#[rt_impl]
impl MulAssign<f32> for Rgb3 {
    fn mul_assign(&mut self, k: f32) {
        self.r *= k;
        self.g *= k;
        self.b *= k;
    }
}

#[rt_impl]
impl Index<usize> for Rgb3 {
    type Output = f32;
    fn index(&self, i: usize) -> &f32 {
        match i {
            0 => &self.r,
            1 => &self.g,
            _ => &self.b,
        }
    }
}

/// A mask with the bitwise operators and `!`.
#[rt_struct(impl BitAnd, impl BitXor, impl Not, impl BitOrAssign<u32>)]
pub struct Mask {
    pub bits: u32,
}

#[rt_impl]
impl BitAnd for Mask {
    type Output = Mask;
    fn bitand(self, o: Mask) -> Mask {
        Mask { bits: self.bits & o.bits }
    }
}

#[rt_impl]
impl BitXor for Mask {
    type Output = Mask;
    fn bitxor(self, o: Mask) -> Mask {
        Mask { bits: self.bits ^ o.bits }
    }
}

#[rt_impl]
impl Not for Mask {
    type Output = Mask;
    fn not(self) -> Mask {
        Mask { bits: !self.bits & 0xff }
    }
}

#[rt_impl]
impl BitOrAssign<u32> for Mask {
    fn bitor_assign(&mut self, b: u32) {
        self.bits |= b << 1;
    }
}

/// A generic helper bounded by std's `Add`: instantiated at a user struct
/// and at `f32`.
#[rt_function]
pub fn sum3<T: Add<Output = T> + Copy>(a: T, b: T, c: T) -> T {
    a + b + c
}

/// Operators in a helper.
#[rt_function]
pub fn mix3(a: Rgb3, b: Rgb3, t: f32) -> Rgb3 {
    a * (1.0 - t) + b * t
}

differential! {
    /// Operators on user structs: the impl's method on every backend.
    fn operator_impls {
        colours(x: f32, y: f32) -> [f32; 12] over pairs(&spread(5, -2.0, 2.0), &spread(4, -1.5, 3.0)), tol CHAINED => {
            let a = Rgb3::new(x, y, x * y);
            let b = Rgb3::new(y, 0.5, -x);
            let c = a + b * 2.0 - -a;
            let mut d = a * b;
            d += c;
            d *= 0.5;
            let m = mix3(a, b, 0.25);
            let q = (a + b) / y;
            let i = 2;
            let s = sum3(a, b, c);
            [c.r, c.g, c.b, d.r, d.g, d.b, m[0] + m[1] + m[i], a.doubled()[1], q.r + q.g + q[2], d[0] + s.g, (a - b).b + sum3(x, y, 1.0), (-(a * x))[1]]
        }
        by_name(x: f32, y: f32) -> [f32; 6] over pairs(&spread(5, -2.0, 2.0), &spread(4, -1.5, 3.0)), tol CHAINED => {
            let a = Rgb3::new(x, y, x * y);
            let b = Rgb3::new(y, 0.5, -x);
            let c = a.add(b.mul(2.0)).sub(a.neg());
            let d = a.mul(b).div(y);
            [c.r, c.g, c.b, d.r, a.halved_sum(b), b.neg().g]
        }
        masks(n: u32, k: u32) -> [u32; 3] over pairs(&[0, 1, 5, 0xf0, 0x7f], &[0, 3, 9]) => {
            let a = Mask { bits: n };
            let b = Mask { bits: k | 0x11 };
            let mut c = !(a & b) ^ a;
            c |= k;
            [c.bits, (!a).bits, (a ^ b & b).bits]
        }
    }
}
