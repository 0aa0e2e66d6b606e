// miss program `cube_miss`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rtp_cube_miss(prd: ptr<function, Radiance>, sky: RtSampler, ground: RtSampler) {
    let d: vec3<f32> = rt_current_ray().direction;
    var c: vec3<f32> = rt_texcube_sample(sky, d).xyz;
    if (d.y < 0.0f) {
        c = ((c * 0.5f) + (rt_texcube_sample(ground, reflect(d, vec3<f32>(0.0, 1.0, 0.0))).xyz / f32(ground.width)));
    }
    (*prd).result = c;
}
