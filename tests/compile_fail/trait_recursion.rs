// A trait method that calls itself: each method is a WGSL function, and
// WGSL has no recursion.
use rt_std::prelude::*;

#[rt_trait]
pub trait Walk {
    fn step(&self, n: u32) -> f32;
}

#[rt_struct(impl Walk)]
pub struct Walker {
    pub v: f32,
}

#[rt_impl]
impl Walk for Walker {
    fn step(&self, n: u32) -> f32 {
        if n == 0 { self.v } else { self.step(n - 1) * 0.5 }
    }
}

#[rt_program(ray_generation)]
pub fn render(#[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    out[i] = Walker { v: i as f32 }.step(3);
}

fn main() {}
