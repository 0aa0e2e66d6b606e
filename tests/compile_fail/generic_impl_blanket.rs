// A blanket impl of a trait over every type: ray programs instantiate a
// generic impl per instance of one generic struct.
use rt_std::prelude::*;

#[rt_trait]
pub trait Scale {
    fn scaled(&self, k: f32) -> f32;
}

#[rt_impl]
impl<T: Copy> Scale for T {
    fn scaled(&self, k: f32) -> f32 {
        k
    }
}

fn main() {}
