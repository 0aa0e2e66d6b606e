// A payload struct declared without #[rt_payload]: the error says which
// attribute to add.
use rt_std::prelude::*;

#[derive(Clone, Copy, Default)]
pub struct Shadow {
    pub attenuation: f32,
}

#[rt_program(any_hit)]
pub fn shadow_hit(prd: &mut Shadow) {
    prd.attenuation = 0.0;
    rt_terminate_ray();
}

fn main() {}
