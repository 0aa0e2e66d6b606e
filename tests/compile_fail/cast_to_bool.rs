// `as bool`: compare with zero instead.
use rt_std::prelude::*;

#[rt_function]
pub fn is_set(flags: u32) -> bool {
    flags as bool
}

fn main() {}
