// A 3D buffer takes (x, y, z): a UVec2 leaves the slice unsaid.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn camera(#[var] mut out: RwBuffer3d<f32>) {
    out[launch_index()] = 1.0;
}

fn main() {}
