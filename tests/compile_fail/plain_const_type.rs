// A plain `const` of the program's own module whose type programs have
// no WGSL for: the error names the constant.
use rt_std::prelude::*;

const WIDE: f64 = 0.5;

#[rt_program(ray_generation)]
pub fn render(#[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    out[i] = WIDE as f32;
}

fn main() {}
