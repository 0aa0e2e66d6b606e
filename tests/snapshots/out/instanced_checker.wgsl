// closest_hit program `instanced_checker`

struct Normals {
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
}

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_bufload_vec3f(b: RtBuffer, i: u32) -> vec3<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec3f(b.offset + i * 3u);
    }
    return vec3<f32>();
}

fn rt_f2i3(x: vec3<f32>) -> vec3<i32> {
    return select(select(vec3<i32>(x), vec3<i32>(2147483647i), x >= vec3<f32>(2147483648.0)), vec3<i32>(0), (bitcast<vec3<u32>>(x) & vec3<u32>(0x7fffffffu)) > vec3<u32>(0x7f800000u));
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtp_instanced_checker(prd: ptr<function, Radiance>, attr: Normals, check_size: f32, colors: RtBuffer) {
    let ray: RtRay = rt_current_ray();
    let world_hit: vec3<f32> = (ray.origin + (rt_t_hit() * ray.direction));
    let object_hit: vec3<f32> = rt_transform_point(1u, world_hit);
    let object_dir: vec3<f32> = rt_transform_vector(1u, ray.direction);
    let back_to_world: vec3<f32> = rt_transform_point(0u, object_hit);
    let cell: vec3<i32> = rt_f2i3(floor((object_hit / check_size)));
    let parity: u32 = u32((((cell.x + cell.y) + cell.z) & 1i));
    let n: vec3<f32> = normalize(rt_transform_normal(0u, attr.shading_normal));
    let facing: f32 = -dot(normalize(object_dir), normalize(attr.shading_normal));
    let drift: f32 = length((back_to_world - world_hit));
    (*prd).result = (((rt_bufload_vec3f(colors, parity) * abs(facing)) * ((n.y * 0.5f) + 0.5f)) + vec3<f32>(drift));
}
