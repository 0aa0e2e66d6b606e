// exception program `report_exception`

fn rt_bufload2_vec4f(b: RtBuffer, i: vec2<u32>) -> vec4<f32> {
    if rt_buf_check2(b, i) {
        return rt_load_vec4f(b.offset + (i.y * b.width + i.x) * 4u);
    }
    return vec4<f32>();
}

fn rt_bufstore2_vec4f(b: RtBuffer, i: vec2<u32>, v: vec4<f32>) {
    if rt_buf_check2(b, i) {
        rt_store_vec4f(b.offset + (i.y * b.width + i.x) * 4u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_vec4f(w: u32, v: vec4<f32>) {
    rt_store_f32(w + 0u, v[0]);
    rt_store_f32(w + 1u, v[1]);
    rt_store_f32(w + 2u, v[2]);
    rt_store_f32(w + 3u, v[3]);
}

fn rtp_report_exception(out_color: RtBuffer) {
    var out_color_1 = out_color;
    let code: u32 = rt_exception_code();
    var tmp: vec3<f32>;
    switch code {
        case 1005u: {
            tmp = vec3<f32>(1.0f, 0.0f, 0.0f);
        }
        case 1021u, 1022u: {
            tmp = vec3<f32>(1.0f, 1.0f, 0.0f);
        }
        default: {
            var tmp_2: vec3<f32>;
            {
                if (code >= 1024u) {
                    let tmp_1 = (code - 1024u);
                    if rt_printf_begin(1286641769u, 1u) {
                        rt_printf_word(tmp_1);
                    }
                }
                tmp_2 = vec3<f32>(1.0f, 0.0f, 1.0f);
            }
            tmp = tmp_2;
        }
    }
    let color: vec3<f32> = tmp;
    let tmp_3 = rt_launch_index();
    rt_bufstore2_vec4f(out_color_1, tmp_3, vec4<f32>(color, 1.0f));
}
