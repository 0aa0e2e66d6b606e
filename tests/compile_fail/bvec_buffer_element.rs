// A bool vector as a buffer element: WGSL's bools have no memory layout
// the host shares; the buffer holds the mask's bits.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn camera(#[var] p: Vec3, #[var] mut out: RwBuffer<BVec3>) {
    out[launch_index().x] = p.cmpgt(Vec3::ZERO);
}

fn main() {}
