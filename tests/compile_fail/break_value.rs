// `break` with a value: WGSL loops are statements.
use rt_std::prelude::*;

#[rt_function]
pub fn first_square_above(limit: u32) -> u32 {
    let mut i = 0u32;
    let found = loop {
        if i * i > limit {
            break i;
        }
        i += 1;
    };
    found
}

fn main() {}
