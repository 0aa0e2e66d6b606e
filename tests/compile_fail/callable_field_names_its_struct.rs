// A struct's `Callable` field whose signature names the struct: legal Rust,
// but the ray compiler resolves a signature's types before the struct.
use rt_std::prelude::*;

#[rt_struct]
pub struct Hops {
    pub next: Callable<fn(Hops, u32) -> u32>,
}

#[rt_program(callable)]
pub fn hop(hops: Hops, x: u32) -> u32 {
    hops.next.call(hops, x)
}

fn main() {}
