// closest_hit program `match_int`

struct Normals {
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
}

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rtf_material_albedo(id: u32) -> vec3<f32> {
    var tmp: vec3<f32>;
    switch id {
        case 0u: {
            tmp = vec3<f32>(0.8f, 0.8f, 0.8f);
        }
        case 1u, 2u: {
            tmp = vec3<f32>(0.9f, 0.1f, 0.1f);
        }
        case 4u, 7u, 9u: {
            tmp = vec3<f32>(0.1f, 0.9f, 0.1f);
        }
        default: {
            tmp = vec3<f32>(0.1f, 0.1f, 0.9f);
        }
    }
    return tmp;
}

fn rtp_match_int(prd: ptr<function, Radiance>, attr: Normals, material: u32) {
    var color: vec3<f32> = rtf_material_albedo(material);
    switch (*prd).depth {
        case 0i: {
            {
            }
        }
        case 1i, 2i: {
            color *= 0.5f;
        }
        case -1i: {
            {
                (*prd).result = vec3<f32>(0.0);
                return;
            }
        }
        default: {
            {
                color *= 0.25f;
            }
        }
    }
    var tmp_1: f32;
    switch (*prd).depth {
        case 0i: {
            tmp_1 = 0.0f;
        }
        default: {
            let d = (*prd).depth;
            tmp_1 = (1.0f / f32(d));
        }
    }
    let bounce_weight: f32 = (1.0f + tmp_1);
    var tmp_2: i32;
    switch (rt_primitive_index() % 4u) {
        case 0u: {
            tmp_2 = 1i;
        }
        case 1u, 3u: {
            tmp_2 = -1i;
        }
        default: {
            let other = (rt_primitive_index() % 4u);
            tmp_2 = (i32(other) * 2i);
        }
    }
    let lobe: i32 = tmp_2;
    let n: vec3<f32> = (attr.shading_normal * f32(lobe));
    (*prd).result = ((color * bounce_weight) * abs(n.z));
}
