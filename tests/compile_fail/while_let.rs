// `while let`: programs loop with while/loop/for.
use rt_std::prelude::*;

#[rt_function]
pub fn count_down(x: i32) -> i32 {
    let mut n = x;
    while let 1..=100 = n {
        n -= 1;
    }
    n
}

fn main() {}
