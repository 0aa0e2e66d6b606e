// `col_mut` gives a place to write through, not a value to hold: ray
// programs have no reference locals.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn camera(#[var] m: Mat3, #[var] mut out: RwBuffer<f32>) {
    let mut n = m;
    let column = n.col_mut(1);
    out[launch_index().x] = column.x;
}

fn main() {}
