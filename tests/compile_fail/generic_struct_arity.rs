// A generic struct named with the wrong number of arguments.
use rt_std::prelude::*;

#[rt_struct]
pub struct Pair<T> {
    pub a: T,
    pub b: T,
}

#[rt_program(ray_generation)]
pub fn render(#[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    let p: Pair<f32, u32> = Pair { a: 1.0, b: 2.0 };
    out[i] = p.a;
}

fn main() {}
