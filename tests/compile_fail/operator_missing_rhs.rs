// `c * 2.0` where the struct implements `Mul` only for itself: the error
// names the impl that is missing.
use rt_std::prelude::*;
use std::ops::Mul;

#[rt_struct(impl Mul)]
pub struct Rgb {
    pub c: Vec3,
}

#[rt_impl]
impl Mul for Rgb {
    type Output = Rgb;
    fn mul(self, o: Rgb) -> Rgb {
        Rgb { c: self.c * o.c }
    }
}

#[rt_program(ray_generation)]
pub fn scale(#[var] out: RwBuffer<f32>) {
    let c = Rgb { c: Vec3::ONE };
    let d = c * 2.0;
    out[0] = d.c.x;
}

fn main() {}
