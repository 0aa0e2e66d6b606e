// exception_code is only meaningful in the exception program.
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    if exception_code() != 0 {
        return;
    }
    prd.result = bg_color;
}

fn main() {}
