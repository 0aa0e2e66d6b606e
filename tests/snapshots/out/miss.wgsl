// miss program `miss`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rtp_miss(prd: ptr<function, Radiance>, bg_color: vec3<f32>) {
    (*prd).result = bg_color;
}
