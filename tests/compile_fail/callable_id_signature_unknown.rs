// An id made in a program where its signature is not known to the ray
// compiler (an assignment's right side is lowered before its place).
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn pick(#[var] base: u32, #[var] mut made: RwBuffer<Callable<fn(u32) -> u32>>) {
    made[0] = Callable::from_id(base);
}

fn main() {}
