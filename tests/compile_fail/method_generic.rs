// A generic method: WGSL functions are monomorphic.
use rt_std::prelude::*;

#[rt_struct(impl)]
pub struct Probe {
    pub x: f32,
}

#[rt_impl]
impl Probe {
    pub fn scaled<T: Into<f32>>(&self, k: T) -> f32 {
        self.x * k.into()
    }
}

fn main() {}
