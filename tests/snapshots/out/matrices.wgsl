// closest_hit program `matrices`

struct Normals {
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
}

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_mat3(w: u32) -> mat3x3<f32> {
    return mat3x3<f32>(rt_load_vec3f(w + 0u), rt_load_vec3f(w + 3u), rt_load_vec3f(w + 6u));
}

fn rt_load_mat4(w: u32) -> mat4x4<f32> {
    return mat4x4<f32>(rt_load_vec4f(w + 0u), rt_load_vec4f(w + 4u), rt_load_vec4f(w + 8u), rt_load_vec4f(w + 12u));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rtp_matrices(prd: ptr<function, Radiance>, attr: Normals, model: mat4x4<f32>, tint: mat3x3<f32>) {
    let n: vec3<f32> = normalize(attr.shading_normal);
    var tmp: vec3<f32>;
    if (abs(n.y) < 0.999f) {
        tmp = vec3<f32>(0.0, 1.0, 0.0);
    } else {
        tmp = vec3<f32>(1.0, 0.0, 0.0);
    }
    let up: vec3<f32> = tmp;
    let t: vec3<f32> = normalize(cross(up, n));
    let b: vec3<f32> = cross(n, t);
    var tbn: mat3x3<f32> = mat3x3<f32>(t, b, n);
    var world_to_tangent: mat3x3<f32> = transpose(tbn);
    let ray: RtRay = rt_current_ray();
    let local_dir: vec3<f32> = (world_to_tangent * -ray.direction);
    let tmp_1 = vec3<f32>(2.0f, 1.0f, 0.5f);
    var scale: mat3x3<f32> = mat3x3<f32>(vec3<f32>(tmp_1[0], 0.0, 0.0), vec3<f32>(0.0, tmp_1[1], 0.0), vec3<f32>(0.0, 0.0, tmp_1[2]));
    let shaded: vec3<f32> = (((tint * scale) * local_dir) + (tint * mat3x3<f32>(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, 0.0, 1.0)))[2u]);
    let hit: vec3<f32> = (model * vec4<f32>((ray.origin + (rt_t_hit() * ray.direction)), 1.0)).xyz;
    let axis: vec3<f32> = (((model * vec4<f32>(vec3<f32>(0.0, 0.0, 1.0), 0.0)).xyz + model[3].xyz) + model[0].xyz);
    var m4: mat4x4<f32> = (((model * mat4x4<f32>(vec4<f32>(1.0, 0.0, 0.0, 0.0), vec4<f32>(0.0, 1.0, 0.0, 0.0), vec4<f32>(0.0, 0.0, 1.0, 0.0), vec4<f32>(0.0, 0.0, 0.0, 1.0))) + mat4x4<f32>()) - (model * 0.5f));
    let clip: vec4<f32> = (((m4 * vec4<f32>(hit, 1.0f)) + (m4 * vec4<f32>(0.0, 0.0, 0.0, 1.0))) + (2.0f * ((m4 * model) * vec4<f32>(1.0, 0.0, 0.0, 0.0))));
    let det: f32 = ((determinant(tbn) + tint[2].z) + tbn[1].x);
    (*prd).result = (((shaded + (axis * det)) + (clip.xyz / clip.w)) * length((mat3x3<f32>() + tbn)[0u]));
}
