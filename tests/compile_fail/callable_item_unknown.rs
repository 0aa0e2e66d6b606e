// `Callable` has `NONE`, `from_id` and `default` in ray programs.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn pick(#[var] mut made: RwBuffer<Callable<fn(u32) -> u32>>) {
    let f = Callable::<fn(u32) -> u32>::new(3);
    made[0] = f;
}

fn main() {}
