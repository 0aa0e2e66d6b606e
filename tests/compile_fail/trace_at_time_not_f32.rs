// `rt_trace_at` takes the ray's time as an `f32`.
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(ray_generation)]
pub fn camera(#[var] top: Object) {
    let mut prd = Radiance { result: Vec3::ZERO };
    let ray = Ray::new(Vec3::ZERO, Vec3::Z, 0, 0.0, 1.0);
    let frame = 3u32;
    rt_trace_at(top, ray, &mut prd, RAY_FLAG_NONE, RAY_MASK_ALL, frame);
}

fn main() {}
