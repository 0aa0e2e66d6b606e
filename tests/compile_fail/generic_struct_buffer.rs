// An instance of a generic struct as a buffer element: the host reads a
// buffer by its element's layout, which a generic struct has not.
use rt_std::prelude::*;

#[rt_struct]
pub struct Pair<T> {
    pub a: T,
    pub b: T,
}

#[rt_program(ray_generation)]
pub fn render(#[var] mut out: RwBuffer<Pair<f32>>) {
    let i = launch_index().x;
    out[i] = Pair { a: 1.0, b: 2.0 };
}

fn main() {}
