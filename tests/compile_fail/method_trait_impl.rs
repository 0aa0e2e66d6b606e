// An impl of one of std's traits under #[rt_impl]: ray programs implement
// traits declared with #[rt_trait].
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
