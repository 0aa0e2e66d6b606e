// An impl of one of std's traits that is not an operator under #[rt_impl]:
// ray programs implement traits declared with #[rt_trait] and std's
// operator traits.
use rt_std::prelude::*;

#[rt_struct]
pub struct Sphere {
    pub radius: f32,
}

#[rt_impl]
impl From<f32> for Sphere {
    fn from(radius: f32) -> Sphere {
        Sphere { radius }
    }
}

fn main() {}
