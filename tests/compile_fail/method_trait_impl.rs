// A trait impl under #[rt_impl]: ray programs have no traits.
use rt_std::prelude::*;

#[rt_struct(impl)]
pub struct Sphere {
    pub radius: f32,
}

#[rt_impl]
impl core::ops::Neg for Sphere {
    type Output = Sphere;
    fn neg(self) -> Sphere {
        Sphere { radius: -self.radius }
    }
}

fn main() {}
