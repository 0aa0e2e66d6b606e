// A tuple pattern with the wrong number of elements in a `match` over a
// tuple (rustc reports it too).
use rt_std::prelude::*;

#[rt_function]
pub fn pick(p: (i32, i32)) -> i32 {
    match p {
        (0, 0, 0) => 1,
        _ => 2,
    }
}

fn main() {}
