// closest_hit program `colour_by_instance`

struct Lit {
    colour: vec3<f32>,
    source: u32,
}

struct MeshData {
    colours: u32,
    gain: f32,
}

fn rt_bufload_MeshData(b: RtBuffer, i: u32) -> MeshData {
    if rt_buf_check(b, i) {
        return rt_load_MeshData(b.offset + i * 2u);
    }
    return MeshData();
}

fn rt_bufload_vec3f(b: RtBuffer, i: u32) -> vec3<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec3f(b.offset + i * 3u);
    }
    return vec3<f32>();
}

fn rt_idload_vec3f(id: u32, i: u32) -> vec3<f32> {
    if rt_bufid_ok(id, 725374594u, false) {
        return rt_bufload_vec3f(rt_bufid(id), i);
    }
    return vec3<f32>();
}

fn rt_load_MeshData(w: u32) -> MeshData {
    return MeshData(rt_load_u32(w + 0u), rt_load_f32(w + 1u));
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

fn rtp_colour_by_instance(prd: ptr<function, Lit>, mesh: u32, meshes: RtBuffer) {
    let m: MeshData = rt_bufload_MeshData(meshes, mesh);
    (*prd).colour = (rt_idload_vec3f(m.colours, rt_primitive_index()) * m.gain);
    (*prd).source = m.colours;
}
