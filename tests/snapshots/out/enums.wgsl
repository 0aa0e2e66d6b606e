// ray_generation program `enums`

struct KindShade {
    color: vec3<f32>,
    hit: u32,
}

struct Light {
    kind: u32,
    power: f32,
}

fn rt_bufload_Light(b: RtBuffer, i: u32) -> Light {
    if rt_buf_check(b, i) {
        return rt_load_Light(b.offset + i * 2u);
    }
    return Light();
}

fn rt_bufload_u32(b: RtBuffer, i: u32) -> u32 {
    if rt_buf_check(b, i) {
        return rt_load_u32(b.offset + i * 1u);
    }
    return u32();
}

fn rt_bufload_vec3f(b: RtBuffer, i: u32) -> vec3<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec3f(b.offset + i * 3u);
    }
    return vec3<f32>();
}

fn rt_bufstore_u32(b: RtBuffer, i: u32, v: u32) {
    if rt_buf_check(b, i) {
        rt_store_u32(b.offset + i * 1u, v);
    }
}

fn rt_bufstore_vec3f(b: RtBuffer, i: u32, v: vec3<f32>) {
    if rt_buf_check(b, i) {
        rt_store_vec3f(b.offset + i * 3u, v);
    }
}

fn rt_load_Light(w: u32) -> Light {
    return Light(rt_load_u32(w + 0u), rt_load_f32(w + 1u));
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

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

fn rt_store_vec3f(w: u32, v: vec3<f32>) {
    rt_store_f32(w + 0u, v[0]);
    rt_store_f32(w + 1u, v[1]);
    rt_store_f32(w + 2u, v[2]);
}

fn rtf_next_material(m: u32) -> u32 {
    var tmp: u32;
    switch m {
        case 0u: {
            tmp = 1u;
        }
        case 1u: {
            tmp = 2u;
        }
        case 2u, default: {
            tmp = 0u;
        }
    }
    return tmp;
}

fn rtp_enums(material: u32, lights: RtBuffer, kinds: RtBuffer, out: RtBuffer) {
    var kinds_1 = kinds;
    var out_1 = out;
    let i: u32 = rt_launch_index().x;
    let light: Light = rt_bufload_Light(lights, i);
    var prd: KindShade = KindShade(vec3<f32>(0.0), material);
    var tmp: f32;
    switch light.kind {
        case 1u: {
            tmp = 1.0f;
        }
        case 4u: {
            tmp = 0.5f;
        }
        case 5u, default: {
            tmp = light.power;
        }
    }
    var weight: f32 = tmp;
    switch rtf_next_material(prd.hit) {
        case 0u: {
            prd.color = vec3<f32>(weight);
        }
        case 1u, 2u, default: {
            {
                weight *= 2.0f;
                prd.color = vec3<f32>(weight, 0.0f, 1.0f);
            }
        }
    }
    if ((prd.hit == 2u) || (light.kind != 4u)) {
        prd.hit = 0u;
    }
    let tmp_2 = i;
    rt_bufstore_u32(kinds_1, tmp_2, light.kind);
    let tmp_3 = i;
    rt_bufstore_vec3f(out_1, tmp_3, (prd.color + vec3<f32>(f32((prd.hit + 5u)))));
}
