// A String: programs have no strings.
use rt_std::prelude::*;

#[rt_function]
pub fn label() -> u32 {
    let name = String::new();
    let _ = name;
    0
}

fn main() {}
