// A generic helper whose type parameter neither a turbofish nor the
// arguments give: rustc infers it from a later use, the lowering types each
// call where it is.
use rt_std::prelude::*;

#[rt_function]
pub fn zero<T: Default>() -> T {
    T::default()
}

#[rt_program(ray_generation)]
pub fn render(#[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    let mut z = zero();
    z = z + i as f32;
    out[i] = z;
}

fn main() {}
