// A bound on a generic struct's parameter: bounds go on its impl block.
use rt_std::prelude::*;

#[rt_struct]
pub struct Pair<T: Copy> {
    pub a: T,
    pub b: T,
}

fn main() {}
