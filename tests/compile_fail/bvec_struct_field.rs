// A bool vector as a struct field: fields are plain data, stored in the
// heap; the struct holds the mask's bits.
use rt_std::prelude::*;

#[rt_struct]
pub struct Hit {
    pub t: f32,
    pub inside: BVec3,
}

#[rt_program(ray_generation)]
pub fn camera(#[var] hits: Buffer<Hit>, #[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    out[i] = hits[i].t;
}

fn main() {}
