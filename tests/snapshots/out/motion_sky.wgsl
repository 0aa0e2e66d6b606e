// miss program `motion_sky`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rtp_motion_sky(prd: ptr<function, Radiance>) {
    (*prd).result = vec3<f32>(0.2f, 0.3f, rt_current_time());
}
