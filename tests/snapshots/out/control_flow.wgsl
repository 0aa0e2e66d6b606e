// closest_hit program `control_flow`

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

fn rtf_bucket(v: f32) -> i32 {
    if (v < 0.0f) {
        return -1i;
    }
    var tmp_2: i32;
    if (v == 0.0f) {
        tmp_2 = 0i;
    } else {
        var tmp_1: i32;
        if (v < 1.0f) {
            tmp_1 = 1i;
        } else {
            var tmp: i32;
            if (v < 10.0f) {
                tmp = 2i;
            } else {
                tmp = 3i;
            }
            tmp_1 = tmp;
        }
        tmp_2 = tmp_1;
    }
    return tmp_2;
}

fn rtp_control_flow(prd: ptr<function, Radiance>, attr: Normals, threshold: f32) {
    if ((*prd).depth > 4i) {
        (*prd).result = vec3<f32>(0.0);
        return;
    }
    let facing: f32 = dot(attr.shading_normal, -rt_current_ray().direction);
    let facing_1: f32 = max(facing, 0.0f);
    let facing_2: f32 = (facing_1 * facing_1);
    var tmp_1: vec3<f32>;
    if (facing_2 > threshold) {
        tmp_1 = vec3<f32>(1.0f, 0.9f, 0.8f);
    } else {
        var tmp: vec3<f32>;
        if (facing_2 > (0.5f * threshold)) {
            tmp = vec3<f32>(0.5f);
        } else {
            tmp = vec3<f32>(0.0);
        }
        tmp_1 = tmp;
    }
    let tint: vec3<f32> = tmp_1;
    var tmp_2: f32;
    if ((*prd).importance <= 0.0f) {
        (*prd).result = tint;
        return;
    } else {
        tmp_2 = (1.0f / (*prd).importance);
    }
    let inv_importance: f32 = tmp_2;
    var tmp_3: f32;
    {
        let k: i32 = rtf_bucket((facing_2 - threshold));
        let base: f32 = (f32(k) * 0.25f);
        tmp_3 = (base + 0.125f);
    }
    let weight: f32 = tmp_3;
    var color: vec3<f32> = ((tint * weight) * inv_importance);
    if (color.x > 1.0f) {
        color.x = 1.0f;
    } else {
        if (color.y > 1.0f) {
            color.y = 1.0f;
        } else {
            color.z = min(color.z, 1.0f);
        }
    }
    {
        let color_1: vec3<f32> = (color * 0.5f);
        (*prd).importance *= length(color_1);
    }
    var tmp_4: vec3<f32>;
    if ((*prd).depth == 0i) {
        tmp_4 = color;
    } else {
        tmp_4 = (color * 0.5f);
    }
    (*prd).result = tmp_4;
}
