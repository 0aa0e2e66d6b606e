// A bool vector as a variable: the host sets variables by value, and a
// bool vector has no layout it shares.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn camera(#[var] which: BVec2, #[var] mut out: RwBuffer<f32>) {
    out[launch_index().x] = Vec2::select(which, Vec2::ONE, Vec2::ZERO).x;
}

fn main() {}
