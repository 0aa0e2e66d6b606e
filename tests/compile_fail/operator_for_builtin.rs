// An operator impl for a built-in type (`2.0 * c`): ray programs take the
// operator on the user's type, with the scalar on the right.
use rt_std::prelude::*;
use std::ops::Mul;

#[rt_struct]
pub struct Rgb {
    pub c: Vec3,
}

#[rt_impl]
impl Mul<Rgb> for f32 {
    type Output = Rgb;
    fn mul(self, o: Rgb) -> Rgb {
        Rgb { c: o.c * self }
    }
}

fn main() {}
