// A generic struct: each WGSL struct has concrete field types.
use rt_std::prelude::*;

#[rt_struct]
pub struct Pair<T> {
    pub a: T,
    pub b: T,
}

fn main() {}
