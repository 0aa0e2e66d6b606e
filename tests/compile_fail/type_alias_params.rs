// A type alias of ray programs takes type parameters only, and its uses
// give it as many arguments as it has.
use rt_std::prelude::*;

#[rt_type]
pub type Row<const N: usize> = [f32; N];

#[rt_struct]
pub struct Pair<T> {
    pub a: T,
    pub b: T,
}

#[rt_type]
pub type Both<T> = Pair<T>;

#[rt_function]
pub fn first(p: Both<f32, u32>) -> f32 {
    p.a
}

fn main() {}
