//! Operator traits for a user struct: `Add`, `Mul` and `Mul<f32>` side by
//! side, `Neg`, `AddAssign` and `Index`, declared with `#[rt_impl]` and
//! listed on the struct (`#[rt_struct(impl Add, ...)]`).
use rt_std::prelude::*;
use std::ops::{Add, AddAssign, Index, Mul, Neg};

/// Lum in three channels.
#[rt_struct(impl Add, impl Mul, impl Mul<f32>, impl Neg, impl AddAssign, impl Index<usize>)]
pub struct Lum {
    pub c: Vec3,
}

#[rt_impl]
impl Add for Lum {
    type Output = Lum;
    fn add(self, o: Lum) -> Lum {
        Lum { c: self.c + o.c }
    }
}

#[rt_impl]
impl Mul for Lum {
    type Output = Self;
    fn mul(self, o: Self) -> Self::Output {
        Lum { c: self.c * o.c }
    }
}

#[rt_impl]
impl Mul<f32> for Lum {
    type Output = Lum;
    fn mul(self, k: f32) -> Lum {
        Lum { c: self.c * k }
    }
}

#[rt_impl]
impl Neg for Lum {
    type Output = Lum;
    fn neg(self) -> Lum {
        Lum { c: -self.c }
    }
}

#[rt_impl]
impl AddAssign for Lum {
    fn add_assign(&mut self, o: Lum) {
        self.c += o.c;
    }
}

#[rt_impl]
impl Index<usize> for Lum {
    type Output = f32;
    fn index(&self, i: usize) -> &f32 {
        &self.c[i]
    }
}

/// A payload carrying light.
#[rt_payload]
pub struct GlowRay {
    pub l: Lum,
}

#[rt_program(miss)]
pub fn lum_miss(prd: &mut GlowRay) {
    let sky = Lum { c: Vec3::new(0.5, 0.7, 1.0) };
    let mut l = prd.l * sky + sky * 0.5;
    l += -prd.l;
    prd.l = l;
    prd.l.c.x = l[1];
}
