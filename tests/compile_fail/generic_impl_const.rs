// An associated constant of a generic block whose type names the block's
// parameter: a WGSL constant has one type. One that names no parameter
// (`HALF`) is one constant for every instance.
use rt_std::prelude::*;

#[rt_struct(impl)]
pub struct Pair<T> {
    pub a: T,
    pub b: T,
}

#[rt_impl]
impl<T: Copy> Pair<T> {
    pub const HALF: f32 = 0.5;
    pub const NONE: Option<T> = None;
}

#[rt_program(ray_generation)]
pub fn render(#[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    out[i] = Pair::<f32>::HALF + Pair::<f32>::NONE.unwrap_or(1.0);
}

fn main() {}
