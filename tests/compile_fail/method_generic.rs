// A generic method's const parameter is an array length: `usize`.
use rt_std::prelude::*;

#[rt_struct(impl)]
pub struct Probe {
    pub x: f32,
}

#[rt_impl]
impl Probe {
    pub fn scaled<const K: u32>(&self) -> f32 {
        self.x * K as f32
    }
}

fn main() {}
