// closest_hit program `tint_by_instance`

struct Normals {
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
}

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rtp_tint_by_instance(prd: ptr<function, Radiance>, attr: Normals) {
    let hue: f32 = (f32((rt_instance_index() % 8u)) / 8.0f);
    var c: vec3<f32> = ((attr.shading_normal * 0.5f) + vec3<f32>(hue));
    if (rt_instance_id() != 4294967295u) {
        c = (c * 0.5f);
    }
    (*prd).result = c;
}
