// A method in a plain `impl` block: programs see only #[rt_impl] blocks.
use rt_std::prelude::*;

#[rt_struct]
pub struct Sphere {
    pub radius: f32,
}

impl Sphere {
    pub fn area(&self) -> f32 {
        12.566371 * self.radius * self.radius
    }
}

#[rt_program(ray_generation)]
pub fn areas(#[var] spheres: Buffer<Sphere>, #[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    out[i] = spheres[i].area();
}

fn main() {}
