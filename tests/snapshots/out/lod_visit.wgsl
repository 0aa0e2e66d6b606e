// visit program `lod_visit`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtp_lod_visit(prd: Radiance, center: vec3<f32>, lod_distances: vec3<f32>, children: u32) -> u32 {
    let ray: RtRay = rt_current_ray();
    let dist: f32 = length((center - ray.origin));
    if ((prd.importance < 0.1f) || (prd.depth > 2i)) {
        return (children - 1u);
    }
    var child: u32 = 0u;
    for (var i: u32 = 0u; i < 3u; i++) {
        if (dist > lod_distances[i]) {
            child = (i + 1u);
        }
    }
    return min(child, (children - 1u));
}
