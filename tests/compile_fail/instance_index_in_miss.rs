// A miss program runs for no instance: there is none to number.
use rt_std::prelude::*;

#[rt_payload]
pub struct Seen {
    pub instance: u32,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Seen) {
    prd.instance = instance_index();
}

fn main() {}
