// A labeled break: WGSL has no loop labels.
use rt_std::prelude::*;

#[rt_function]
pub fn first_pair(n: u32) -> u32 {
    let mut found = 0u32;
    'outer: for i in 0..n {
        for j in 0..n {
            if i * j == 12 {
                found = i;
                break 'outer;
            }
        }
    }
    found
}

fn main() {}
