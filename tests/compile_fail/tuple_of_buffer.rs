// A tuple holding a buffer handle: tuples hold plain values.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn camera(#[var] samples: Buffer<f32>, #[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    let pair = (samples, i);
    out[i] = pair.0[pair.1];
}

fn main() {}
