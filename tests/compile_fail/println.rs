// println!: programs print with rt_printf!.
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    println!("miss: {}", bg_color);
    prd.result = bg_color;
}

fn main() {}
