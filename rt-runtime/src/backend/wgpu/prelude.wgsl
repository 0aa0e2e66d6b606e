// ---- rt-runtime megakernel prelude ----
// The real implementations of the stubs every program was validated
// against (same names and signatures), plus the state and scene access the
// generated traversal and dispatch code use.

// The records shared with the compiler (RtRay, RtAabb, RtBuffer,
// RtSampler), the heap binding, rt_f32_from_bits and RT_F32_MAX (how
// infinity, NaN and the f32 extreme are spelled), the RT_EXC_* codes, the RT_RAY_FLAG_*
// flags, the launch uniform's struct RtLaunch and the RT_INST_* and
// RT_NODE_* layout constants come first, from rt-abi (see kernel.rs).


@group(0) @binding(1) var<storage, read> rt_scene: array<u32>;
@group(0) @binding(2) var<storage, read_write> rt_log: array<atomic<u32>>;
@group(0) @binding(3) var<uniform> rt_launch: RtLaunch;

const RT_NONE: u32 = 0xffffffffu;

// Per-invocation state behind the intrinsics.
var<private> rt_idx: vec2<u32>;
var<private> rt_exc: u32;
var<private> rt_ray: RtRay;
// The current ray's time (rt_current_time), and the time of the next trace
// (rt_set_trace_time, before an rt_trace_at): every trace takes rt_next_time
// and puts it back to 0, so a trace without a time is at time 0.
var<private> rt_time: f32;
var<private> rt_next_time: f32;
var<private> rt_t: f32;
var<private> rt_prim: u32;
var<private> rt_o2w: mat4x4<f32>;
var<private> rt_w2o: mat4x4<f32>;
var<private> rt_ignored: bool;
var<private> rt_terminated: bool;
// The search in progress (any hit and intersection programs cannot trace,
// so searches never nest).
var<private> rt_s_flags: u32;
var<private> rt_s_ray_type: u32;
var<private> rt_s_done: bool;
var<private> rt_s_tmax: f32;
var<private> rt_s_gi: u32;
var<private> rt_s_inst: u32;
var<private> rt_s_oray: RtRay;
var<private> rt_c_t: f32;
var<private> rt_c_ok: bool;
var<private> rt_c_prim: u32;
var<private> rt_h_found: bool;
var<private> rt_h_t: f32;
var<private> rt_h_gi: u32;
var<private> rt_h_prim: u32;
var<private> rt_h_mat: u32;
var<private> rt_h_inst: u32;
var<private> rt_h_custom: bool;
var<private> rt_h_bary: vec2<f32>;
var<private> rt_c_bary: vec2<f32>;
var<private> rt_c_custom: bool;
var<private> rt_print_on: bool;
// The current ray's hit kind (0 none, 1 a triangle's front, 2 its back,
// 3 a custom primitive; rt-std's HIT_*), flags and mask.
var<private> rt_hk: u32;
var<private> rt_rflags: u32;
var<private> rt_rmask: u32;
// Instances (rt-std's instance_index, instance_id): the path a search
// reached the instance it searches by (rt_s_ipath) and the committed hit's
// (rt_h_ipath), each (the instance index of its geometry group's first
// geometry instance, the innermost instance id above it or RT_NONE); the
// current hit's (rt_icur: path, instance record, geometry instance),
// resolved only when a program asks (rt_instance_of).
var<private> rt_s_ipath: vec2<u32>;
var<private> rt_h_ipath: vec2<u32>;
var<private> rt_icur: vec4<u32>;
// Rays this invocation traced (added to rt_log[2] at the end).
var<private> rt_rays: u32;

// rt_exc_bit(code), the bit of code's kind in the launch's mask of enabled
// kinds, is generated from rt_abi::constants::exception_kind_bit
// (rt_abi::wgsl::exception_kind_bits) before this file.

fn rt_raise(code: u32) {
    if rt_exc == 0u && (rt_launch.exceptions & rt_exc_bit(code)) != 0u {
        rt_exc = code;
    }
}

fn rt_f(w: u32) -> f32 { return bitcast<f32>(rt_scene[w]); }
fn rt_v3(w: u32) -> vec3<f32> { return vec3<f32>(rt_f(w), rt_f(w + 1u), rt_f(w + 2u)); }
fn rt_m4(w: u32) -> mat4x4<f32> {
    return mat4x4<f32>(
        vec4<f32>(rt_f(w), rt_f(w + 1u), rt_f(w + 2u), rt_f(w + 3u)),
        vec4<f32>(rt_f(w + 4u), rt_f(w + 5u), rt_f(w + 6u), rt_f(w + 7u)),
        vec4<f32>(rt_f(w + 8u), rt_f(w + 9u), rt_f(w + 10u), rt_f(w + 11u)),
        vec4<f32>(rt_f(w + 12u), rt_f(w + 13u), rt_f(w + 14u), rt_f(w + 15u)));
}

fn rt_load_RtBuffer(w: u32) -> RtBuffer { return RtBuffer(rt_hw(w), rt_hw(w + 1u), rt_hw(w + 2u), rt_hw(w + 3u)); }
fn rt_load_RtSampler(w: u32) -> RtSampler { return RtSampler(rt_hw(w), rt_hw(w + 1u), rt_hw(w + 2u), rt_hw(w + 3u)); }
fn rt_load_RtSampler3d(w: u32) -> RtSampler3d { return RtSampler3d(rt_hw(w), rt_hw(w + 1u), rt_hw(w + 2u), rt_hw(w + 3u), rt_hw(w + 4u)); }

fn rt_buf_check(b: RtBuffer, i: u32) -> bool {
    if i < b.len { return true; }
    rt_raise(RT_EXC_BUFFER_INDEX);
    return false;
}
fn rt_buf_check2(b: RtBuffer, i: vec2<u32>) -> bool {
    if i.x < b.width && i.y < b.height { return true; }
    rt_raise(RT_EXC_BUFFER_INDEX);
    return false;
}
// A 3D buffer's size: its depth is what its length leaves (width * height
// fits: the host checked width * height * depth).
fn rt_buf_size3(b: RtBuffer) -> vec3<u32> {
    var d = 0u;
    if b.width != 0u && b.height != 0u {
        d = b.len / (b.width * b.height);
    }
    return vec3<u32>(b.width, b.height, d);
}
fn rt_buf_check3(b: RtBuffer, i: vec3<u32>) -> bool {
    if all(i < rt_buf_size3(b)) { return true; }
    rt_raise(RT_EXC_BUFFER_INDEX);
    return false;
}

// Bindless buffer ids through the launch's buffer table
// (rt_abi::records::BufferTable): id k names the entry k - 1, 0 none.
fn rt_bufid_ok(id: u32, tag: u32, writable: bool) -> bool {
    let t = rt_launch.buffer_table;
    if id != 0u && id <= rt_hw(t) {
        let e = t + 1u + (id - 1u) * RT_BUFID_WORDS;
        if rt_hw(e + RT_BUFID_TAG) == tag && (!writable || rt_hw(e + RT_BUFID_WRITABLE) != 0u) {
            return true;
        }
    }
    rt_raise(RT_EXC_BUFFER_ID);
    return false;
}
fn rt_bufid(id: u32) -> RtBuffer {
    let e = rt_launch.buffer_table + 1u + (id - 1u) * RT_BUFID_WORDS;
    let len = rt_hw(e + RT_BUFID_LEN);
    return RtBuffer(rt_hw(e + RT_BUFID_OFFSET), len, len, 1u);
}

// rt_idx is the index in the launch's grid, whose rows are a 3D launch's
// rows of every slice in turn (rt_launch.depth slices).
fn rt_launch_index() -> vec2<u32> {
    if rt_launch.depth <= 1u { return rt_idx; }
    return vec2<u32>(rt_idx.x, rt_idx.y % (rt_launch.dim.y / rt_launch.depth));
}
fn rt_launch_dim() -> vec2<u32> { return vec2<u32>(rt_launch.dim.x, rt_launch.dim.y / max(rt_launch.depth, 1u)); }
fn rt_launch_index_3d() -> vec3<u32> {
    let h = rt_launch.dim.y / max(rt_launch.depth, 1u);
    return vec3<u32>(rt_idx.x, rt_idx.y % h, rt_idx.y / h);
}
fn rt_launch_dim_3d() -> vec3<u32> { return vec3<u32>(rt_launch_dim(), max(rt_launch.depth, 1u)); }
fn rt_current_ray() -> RtRay { return rt_ray; }
fn rt_t_hit() -> f32 { return rt_t; }
fn rt_current_time() -> f32 { return rt_time; }
// A time that is not finite traces at 0, as on the CPU backend.
fn rt_set_trace_time(time: f32) {
    rt_next_time = select(0.0, time, abs(time) <= RT_F32_MAX);
}
fn rt_primitive_index() -> u32 { return rt_prim; }
fn rt_exception_code() -> u32 { return rt_exc; }
fn rt_is_triangle_hit() -> bool { return rt_hk == 1u || rt_hk == 2u; }
fn rt_is_triangle_hit_front_face() -> bool { return rt_hk == 1u; }
fn rt_is_triangle_hit_back_face() -> bool { return rt_hk == 2u; }
fn rt_ray_flags() -> u32 { return rt_rflags; }
fn rt_ray_mask() -> u32 { return rt_rmask; }
fn rt_instance_index() -> u32 { return rt_instance_of(rt_icur).x; }
fn rt_instance_id() -> u32 { return rt_instance_of(rt_icur).y; }

// The instance index and id of geometry instance c.w reached through
// instance record c.z on path c.xy (see rt_icur): the path's index plus the
// geometry instance's place in its geometry group; the id of the geometry
// instance, else of the record's chain of transforms, else the path's.
// The record's RT_INST_GIS table is [count, geometry instances.., their
// ids..] of its geometry group (rt-runtime's link::instances).
fn rt_instance_of(c: vec4<u32>) -> vec2<u32> {
    let ib = rt_scene[1] + c.z * RT_INST_WORDS;
    let t = rt_scene[ib + RT_INST_GIS];
    let n = rt_scene[t];
    var k = 0u;
    while k < n && rt_scene[t + 1u + k] != c.w {
        k = k + 1u;
    }
    var id = c.y;
    if rt_scene[ib + RT_INST_ID] != RT_NONE {
        id = rt_scene[ib + RT_INST_ID];
    }
    if k < n && rt_scene[t + 1u + n + k] != RT_NONE {
        id = rt_scene[t + 1u + n + k];
    }
    return vec2<u32>(c.x + k, id);
}
fn rt_ignore_intersection() { rt_ignored = true; }
fn rt_terminate_ray() { rt_terminated = true; }
fn rt_throw(code: u32) { rt_raise(code); }

fn rt_get_transform(kind: u32) -> mat4x4<f32> {
    if kind == 0u { return rt_o2w; }
    return rt_w2o;
}
fn rt_transform_point(kind: u32, p: vec3<f32>) -> vec3<f32> {
    if kind == 0u { return (rt_o2w * vec4<f32>(p, 1.0)).xyz; }
    return (rt_w2o * vec4<f32>(p, 1.0)).xyz;
}
fn rt_transform_vector(kind: u32, v: vec3<f32>) -> vec3<f32> {
    if kind == 0u { return (rt_o2w * vec4<f32>(v, 0.0)).xyz; }
    return (rt_w2o * vec4<f32>(v, 0.0)).xyz;
}
fn rt_transform_normal(kind: u32, n: vec3<f32>) -> vec3<f32> {
    if kind == 0u { return (transpose(rt_w2o) * vec4<f32>(n, 0.0)).xyz; }
    return (transpose(rt_o2w) * vec4<f32>(n, 0.0)).xyz;
}

fn rt_potential_intersection(t: f32) -> bool {
    rt_c_ok = t > rt_s_oray.tmin && t < rt_s_tmax;
    if rt_c_ok {
        rt_c_t = t;
    }
    return rt_c_ok;
}

// ---- textures: RGBA f32 texels in the heap, sampled as rt-std's CPU
// sampler does (texel centres at (i + 0.5) / size, wrap on texel indices).
// RtSampler.mode: wrap (bits 0-7), filter (bit 8: linear) and index mode
// (bit 9: coordinates in texels), mip filter (16-23: 1 linear), level count
// (24-31); the levels follow each other from level 0, level l being
// max(1, size >> l).
fn rt_tex_wrap(i: i32, n: i32, mode: u32) -> u32 {
    if mode == 1u { return u32(clamp(i, 0, n - 1)); }
    if mode == 2u {
        let p = 2 * n;
        var m = i % p;
        if m < 0 { m = m + p; }
        if m >= n { m = p - 1 - m; }
        return u32(m);
    }
    var m = i % n;
    if m < 0 { m = m + n; }
    return u32(m);
}
// Level l's first texel word and its size; l < the level count.
struct RtTexLevel {
    offset: u32,
    size: vec2<u32>,
}
fn rt_tex_level(s: RtSampler, l: u32) -> RtTexLevel {
    var offset = s.offset;
    var size = vec2<u32>(s.width, s.height);
    for (var k = 0u; k < l; k = k + 1u) {
        offset = offset + size.x * size.y * 4u;
        size = max(size >> vec2<u32>(1u), vec2<u32>(1u));
    }
    return RtTexLevel(offset, size);
}
fn rt_texel(lv: RtTexLevel, x: u32, y: u32) -> vec4<f32> {
    let w = lv.offset + (y * lv.size.x + x) * 4u;
    return vec4<f32>(bitcast<f32>(rt_hw(w)), bitcast<f32>(rt_hw(w + 1u)), bitcast<f32>(rt_hw(w + 2u)), bitcast<f32>(rt_hw(w + 3u)));
}
fn rt_tex_fetch(s: RtSampler, texel: vec2<u32>) -> vec4<f32> {
    if s.width == 0u || s.height == 0u { return vec4<f32>(); }
    return rt_texel(rt_tex_level(s, 0u), min(texel.x, s.width - 1u), min(texel.y, s.height - 1u));
}
fn rt_tex_sample_level(s: RtSampler, lv: RtTexLevel, uv_in: vec2<f32>) -> vec4<f32> {
    let finite = abs(uv_in) <= vec2<f32>(RT_F32_MAX);
    let uv = select(vec2<f32>(0.0), uv_in, finite);
    let wrap = s.mode & 0xffu;
    let linear = ((s.mode >> 8u) & 1u) != 0u;
    let n = vec2<i32>(lv.size);
    var p = uv * vec2<f32>(lv.size);
    if ((s.mode >> 9u) & 1u) != 0u { p = uv; }
    if !linear {
        let i = vec2<i32>(floor(p));
        return rt_texel(lv, rt_tex_wrap(i.x, n.x, wrap), rt_tex_wrap(i.y, n.y, wrap));
    }
    let q = p - 0.5;
    let f = floor(q);
    let a = q - f;
    let i = vec2<i32>(f);
    let x0 = rt_tex_wrap(i.x, n.x, wrap);
    let x1 = rt_tex_wrap(i.x + 1, n.x, wrap);
    let y0 = rt_tex_wrap(i.y, n.y, wrap);
    let y1 = rt_tex_wrap(i.y + 1, n.y, wrap);
    let top = rt_texel(lv, x0, y0) * (1.0 - a.x) + rt_texel(lv, x1, y0) * a.x;
    let bottom = rt_texel(lv, x0, y1) * (1.0 - a.x) + rt_texel(lv, x1, y1) * a.x;
    return top * (1.0 - a.y) + bottom * a.y;
}
fn rt_tex_sample(s: RtSampler, uv: vec2<f32>) -> vec4<f32> {
    if s.width == 0u || s.height == 0u { return vec4<f32>(); }
    return rt_tex_sample_level(s, rt_tex_level(s, 0u), uv);
}
// Vulkan's level selection (rt-std's texture docs): d = clamp(lod, 0,
// levels - 1), NaN as 0; the nearest level rounds a half down, the linear
// mip filter blends floor(d) and the next level by the fraction.
fn rt_tex_sample_lod(s: RtSampler, uv: vec2<f32>, lod: f32) -> vec4<f32> {
    if s.width == 0u || s.height == 0u { return vec4<f32>(); }
    let levels = max(s.mode >> 24u, 1u);
    let last = f32(levels - 1u);
    var d = 0.0;
    // By the bits: a NaN compares unordered, which compilers may assume away.
    if (bitcast<u32>(lod) & 0x7fffffffu) <= 0x7f800000u { d = clamp(lod, 0.0, last); }
    if ((s.mode >> 16u) & 0xffu) == 0u {
        return rt_tex_sample_level(s, rt_tex_level(s, u32(ceil(d + 0.5) - 1.0)), uv);
    }
    let hi = floor(d);
    let delta = d - hi;
    let l = u32(hi);
    let a = rt_tex_sample_level(s, rt_tex_level(s, l), uv);
    if delta == 0.0 { return a; }
    let b = rt_tex_sample_level(s, rt_tex_level(s, min(l + 1u, levels - 1u)), uv);
    return a * (1.0 - delta) + b * delta;
}
// The LOD of a footprint dx, dy (in normalised coordinates): log2 of its
// longer side in level-0 texels, as OpenGL and Vulkan define it. A NaN side
// counts as 0, as f32::max on the CPU ignores a NaN (WGSL's max may not).
// (rt_tex_side takes a side's length: 2D and 3D footprints share it.)
fn rt_tex_side(l: f32) -> f32 {
    if (bitcast<u32>(l) & 0x7fffffffu) <= 0x7f800000u { return l; }
    return 0.0;
}
fn rt_tex_sample_grad(s: RtSampler, uv: vec2<f32>, dx: vec2<f32>, dy: vec2<f32>) -> vec4<f32> {
    let size = vec2<f32>(f32(s.width), f32(s.height));
    let rho = max(rt_tex_side(length(dx * size)), rt_tex_side(length(dy * size)));
    return rt_tex_sample_lod(s, uv, log2(rho));
}

// Vulkan's level selection for 3D and cube samplers, as rt_tex_sample_lod
// makes it: level lo blended with level hi by t (t = 0: lo alone).
struct RtTexMip {
    lo: u32,
    hi: u32,
    t: f32,
}
fn rt_tex_mip(mode: u32, lod: f32) -> RtTexMip {
    let levels = max(mode >> 24u, 1u);
    let last = f32(levels - 1u);
    var d = 0.0;
    if (bitcast<u32>(lod) & 0x7fffffffu) <= 0x7f800000u { d = clamp(lod, 0.0, last); }
    if ((mode >> 16u) & 0xffu) == 0u {
        let l = u32(ceil(d + 0.5) - 1.0);
        return RtTexMip(l, l, 0.0);
    }
    let lo = floor(d);
    return RtTexMip(u32(lo), u32(min(lo + 1.0, last)), d - lo);
}

// 3D textures (rt-std's Sampler3d): texel (x, y, z) of a level at
// x + y * width + z * width * height of it, the levels one after the
// other, level l max(1, size >> l); the 2D rules with a third axis.
struct RtTexLevel3 {
    offset: u32,
    size: vec3<u32>,
}
fn rt_tex3_level(s: RtSampler3d, l: u32) -> RtTexLevel3 {
    var offset = s.offset;
    var size = vec3<u32>(s.width, s.height, s.depth);
    for (var k = 0u; k < l; k = k + 1u) {
        offset = offset + size.x * size.y * size.z * 4u;
        size = max(size >> vec3<u32>(1u), vec3<u32>(1u));
    }
    return RtTexLevel3(offset, size);
}
fn rt_texel3(lv: RtTexLevel3, x: u32, y: u32, z: u32) -> vec4<f32> {
    let w = lv.offset + ((z * lv.size.y + y) * lv.size.x + x) * 4u;
    return vec4<f32>(bitcast<f32>(rt_hw(w)), bitcast<f32>(rt_hw(w + 1u)), bitcast<f32>(rt_hw(w + 2u)), bitcast<f32>(rt_hw(w + 3u)));
}
fn rt_tex3_fetch(s: RtSampler3d, texel: vec3<u32>) -> vec4<f32> {
    if s.width == 0u || s.height == 0u || s.depth == 0u { return vec4<f32>(); }
    let t = min(texel, vec3<u32>(s.width, s.height, s.depth) - 1u);
    return rt_texel3(rt_tex3_level(s, 0u), t.x, t.y, t.z);
}
fn rt_tex3_sample_level(s: RtSampler3d, lv: RtTexLevel3, uvw_in: vec3<f32>) -> vec4<f32> {
    let finite = abs(uvw_in) <= vec3<f32>(RT_F32_MAX);
    let uvw = select(vec3<f32>(0.0), uvw_in, finite);
    let wrap = s.mode & 0xffu;
    let n = vec3<i32>(lv.size);
    // Array-index mode (bit 9): coordinates in texels.
    var p = uvw * vec3<f32>(lv.size);
    if ((s.mode >> 9u) & 1u) != 0u { p = uvw; }
    if ((s.mode >> 8u) & 1u) == 0u {
        let i = vec3<i32>(floor(p));
        return rt_texel3(lv, rt_tex_wrap(i.x, n.x, wrap), rt_tex_wrap(i.y, n.y, wrap), rt_tex_wrap(i.z, n.z, wrap));
    }
    let q = p - 0.5;
    let f = floor(q);
    let a = q - f;
    let i = vec3<i32>(f);
    let x0 = rt_tex_wrap(i.x, n.x, wrap);
    let x1 = rt_tex_wrap(i.x + 1, n.x, wrap);
    let y0 = rt_tex_wrap(i.y, n.y, wrap);
    let y1 = rt_tex_wrap(i.y + 1, n.y, wrap);
    let z0 = rt_tex_wrap(i.z, n.z, wrap);
    let z1 = rt_tex_wrap(i.z + 1, n.z, wrap);
    let top0 = rt_texel3(lv, x0, y0, z0) * (1.0 - a.x) + rt_texel3(lv, x1, y0, z0) * a.x;
    let bottom0 = rt_texel3(lv, x0, y1, z0) * (1.0 - a.x) + rt_texel3(lv, x1, y1, z0) * a.x;
    let top1 = rt_texel3(lv, x0, y0, z1) * (1.0 - a.x) + rt_texel3(lv, x1, y0, z1) * a.x;
    let bottom1 = rt_texel3(lv, x0, y1, z1) * (1.0 - a.x) + rt_texel3(lv, x1, y1, z1) * a.x;
    let near = top0 * (1.0 - a.y) + bottom0 * a.y;
    let far = top1 * (1.0 - a.y) + bottom1 * a.y;
    return near * (1.0 - a.z) + far * a.z;
}
fn rt_tex3_sample(s: RtSampler3d, uvw: vec3<f32>) -> vec4<f32> {
    if s.width == 0u || s.height == 0u || s.depth == 0u { return vec4<f32>(); }
    return rt_tex3_sample_level(s, rt_tex3_level(s, 0u), uvw);
}
fn rt_tex3_sample_lod(s: RtSampler3d, uvw: vec3<f32>, lod: f32) -> vec4<f32> {
    if s.width == 0u || s.height == 0u || s.depth == 0u { return vec4<f32>(); }
    let m = rt_tex_mip(s.mode, lod);
    let a = rt_tex3_sample_level(s, rt_tex3_level(s, m.lo), uvw);
    if m.t == 0.0 { return a; }
    let b = rt_tex3_sample_level(s, rt_tex3_level(s, m.hi), uvw);
    return a * (1.0 - m.t) + b * m.t;
}
// rt_tex_sample_grad with a third axis.
fn rt_tex3_sample_grad(s: RtSampler3d, uvw: vec3<f32>, dx: vec3<f32>, dy: vec3<f32>) -> vec4<f32> {
    let size = vec3<f32>(f32(s.width), f32(s.height), f32(s.depth));
    let rho = max(rt_tex_side(length(dx * size)), rt_tex_side(length(dy * size)));
    return rt_tex3_sample_lod(s, uvw, log2(rho));
}

// Cube maps (rt-std's SamplerCube): an RtSampler of six square faces, +x,
// -x, +y, -y, +z, -z, per level (level l: six faces of side
// max(1, width >> l), the levels one after the other); the face and its
// coordinates by Vulkan's table (ties to z, then y, then x; a non-finite
// component as 0, the zero direction at face +z's centre), sampled on the
// face clamped to its edges.
struct RtCubeFace {
    face: u32,
    st: vec2<f32>,
}
fn rt_texcube_face(dir: vec3<f32>) -> RtCubeFace {
    let finite = abs(dir) <= vec3<f32>(RT_F32_MAX);
    let d = select(vec3<f32>(0.0), dir, finite);
    let a = abs(d);
    var face = 0u;
    var sc = 0.0;
    var tc = 0.0;
    var rc = 0.0;
    if a.z >= a.x && a.z >= a.y {
        rc = a.z;
        tc = -d.y;
        if d.z >= 0.0 { face = 4u; sc = d.x; } else { face = 5u; sc = -d.x; }
    } else if a.y >= a.x {
        rc = a.y;
        sc = d.x;
        if d.y >= 0.0 { face = 2u; tc = d.z; } else { face = 3u; tc = -d.z; }
    } else {
        rc = a.x;
        tc = -d.y;
        if d.x >= 0.0 { face = 0u; sc = -d.z; } else { face = 1u; sc = d.z; }
    }
    var st = vec2<f32>(0.5);
    if rc != 0.0 { st = vec2<f32>(0.5 * (sc / rc) + 0.5, 0.5 * (tc / rc) + 0.5); }
    return RtCubeFace(face, st);
}
// Face f of level l as a 2D level.
fn rt_texcube_level(s: RtSampler, l: u32, f: u32) -> RtTexLevel {
    var offset = s.offset;
    var side = s.width;
    for (var k = 0u; k < l; k = k + 1u) {
        offset = offset + 6u * side * side * 4u;
        side = max(side >> 1u, 1u);
    }
    return RtTexLevel(offset + f * side * side * 4u, vec2<u32>(side, side));
}
fn rt_texcube_sample(s: RtSampler, dir: vec3<f32>) -> vec4<f32> {
    if s.width == 0u { return vec4<f32>(); }
    let c = rt_texcube_face(dir);
    return rt_tex_sample_level(s, rt_texcube_level(s, 0u, c.face), c.st);
}
fn rt_texcube_sample_lod(s: RtSampler, dir: vec3<f32>, lod: f32) -> vec4<f32> {
    if s.width == 0u { return vec4<f32>(); }
    let c = rt_texcube_face(dir);
    let m = rt_tex_mip(s.mode, lod);
    let a = rt_tex_sample_level(s, rt_texcube_level(s, m.lo, c.face), c.st);
    if m.t == 0.0 { return a; }
    let b = rt_tex_sample_level(s, rt_texcube_level(s, m.hi, c.face), c.st);
    return a * (1.0 - m.t) + b * m.t;
}

// Bindless sampler ids through the launch's sampler table
// (rt_abi::records::SamplerTable), right after the buffer table: id k names
// the entry k - 1, 0 none. An id of no sampler, or of one of another shape,
// reads as an empty sampler (every sample zero, size 0) after raising.
fn rt_texid_entry(id: u32, shape: u32) -> u32 {
    let t = rt_launch.buffer_table + 1u + rt_hw(rt_launch.buffer_table) * RT_BUFID_WORDS;
    if id != 0u && id <= rt_hw(t) {
        let e = t + 1u + (id - 1u) * RT_TEXID_WORDS;
        if rt_hw(e + RT_TEXID_SHAPE) == shape { return e; }
    }
    rt_raise(RT_EXC_TEXTURE_ID);
    return 0u;
}
fn rt_texid(id: u32, shape: u32) -> RtSampler {
    let e = rt_texid_entry(id, shape);
    if e == 0u { return RtSampler(0u, 0u, 0u, 0u); }
    return RtSampler(rt_hw(e + RT_TEXID_OFFSET), rt_hw(e + RT_TEXID_WIDTH), rt_hw(e + RT_TEXID_HEIGHT), rt_hw(e + RT_TEXID_MODE));
}
fn rt_texid3(id: u32) -> RtSampler3d {
    let e = rt_texid_entry(id, RT_TEXID_3D);
    if e == 0u { return RtSampler3d(0u, 0u, 0u, 0u, 0u); }
    return RtSampler3d(rt_hw(e + RT_TEXID_OFFSET), rt_hw(e + RT_TEXID_WIDTH), rt_hw(e + RT_TEXID_HEIGHT), rt_hw(e + RT_TEXID_DEPTH), rt_hw(e + RT_TEXID_MODE));
}

// ---- rt_printf!: records of (format id, launch index, word count, words)
// after the exception records in rt_log. rt_log: [0] exceptions, [1] print
// words used, [2] rays traced, [3] unused, then exceptions, then prints.
fn rt_printf_begin(format: u32, words: u32) -> bool {
    rt_print_on = false;
    if rt_launch.print_enabled == 0u { return false; }
    if rt_launch.print_filter.x != RT_NONE && any(rt_launch.print_filter != rt_idx) { return false; }
    let at = atomicAdd(&rt_log[1], words + 4u);
    let base = 4u + rt_launch.log_capacity * 3u;
    if at + words + 4u > arrayLength(&rt_log) - base { return false; }
    atomicStore(&rt_log[base + at], format);
    atomicStore(&rt_log[base + at + 1u], rt_idx.x);
    atomicStore(&rt_log[base + at + 2u], rt_idx.y);
    atomicStore(&rt_log[base + at + 3u], words);
    rt_print_pos = base + at + 4u;
    rt_print_on = true;
    return true;
}
var<private> rt_print_pos: u32;
fn rt_printf_word(word: u32) {
    if rt_print_on {
        atomicStore(&rt_log[rt_print_pos], word);
        rt_print_pos = rt_print_pos + 1u;
    }
}

fn rt_log_exception() {
    let i = atomicAdd(&rt_log[0], 1u);
    if i < rt_launch.log_capacity {
        atomicStore(&rt_log[4u + i * 3u], rt_idx.x);
        atomicStore(&rt_log[4u + i * 3u + 1u], rt_idx.y);
        atomicStore(&rt_log[4u + i * 3u + 2u], rt_exc);
    }
}

// The default exception program (an entry point without one): magenta at
// the launch index of the ray-generation program's output image.
fn rt_default_exception(b: RtBuffer) {
    if rt_idx.x < b.width && rt_idx.y < b.height {
        let w = b.offset + (rt_idx.y * b.width + rt_idx.x) * 4u;
        rt_hw_set(w, bitcast<u32>(1.0));
        rt_hw_set(w + 1u, 0u);
        rt_hw_set(w + 2u, bitcast<u32>(1.0));
        rt_hw_set(w + 3u, bitcast<u32>(1.0));
    }
}

// ---- scene access ----
// rt_scene header: [0] node table, [1] instance table, [2] geometry
// instance table, [3] hit record table, [4] ray type count, [5] miss
// records, [6] intersection records, [7] node count, [8 + s] base of
// section s when it shares rt_scene's binding (kernel.rs `SCENE_SECTIONS`).
// BVH offsets (instance and node-table words) are in the BVH section.
fn rt_valid_ray(r: RtRay) -> bool {
    let big = vec3<f32>(RT_F32_MAX);
    return all(abs(r.origin) <= big) && all(abs(r.direction) <= big) && r.tmin == r.tmin && r.tmax == r.tmax;
}

// A BVH node's words live in the BVH section (`rt_node_word`).
fn rt_node_v3(w: u32) -> vec3<f32> {
    return vec3<f32>(bitcast<f32>(rt_node_word(w)), bitcast<f32>(rt_node_word(w + 1u)), bitcast<f32>(rt_node_word(w + 2u)));
}

// Whether a ray with mask `r` enters a node or chain of nodes with
// visibility word `masks` (compute/scene.rs `visibility`): each of its four
// byte masks shares a bit with `r`.
fn rt_visible(masks: u32, r: u32) -> bool {
    let m = masks & ((r & 0xffu) * 0x01010101u);
    return (m & 0xffu) != 0u && (m & 0xff00u) != 0u && (m & 0xff0000u) != 0u && (m & 0xff000000u) != 0u;
}

// 1 / d for the slab tests, finite: a zero component (an axis-aligned
// ray) gives +-1e30, not infinity. WGSL lets a compiler assume no
// infinities, and lavapipe's does: with 1.0 / 0.0 the instance-level slab
// test of a group missed every ray parallel to an axis.
fn rt_safe_inv(d: vec3<f32>) -> vec3<f32> {
    let m = max(abs(d), vec3<f32>(1e-30));
    return select(vec3<f32>(1.0), vec3<f32>(-1.0), d < vec3<f32>(0.0)) / m;
}

fn rt_aabb_hit(w: u32, o: vec3<f32>, inv: vec3<f32>, tmin: f32, tmax: f32) -> f32 {
    let t0 = (rt_node_v3(w) - o) * inv;
    let t1 = (rt_node_v3(w + 3u) - o) * inv;
    let lo = min(t0, t1);
    let hi = max(t0, t1);
    let near = max(max(max(lo.x, lo.y), lo.z), tmin);
    let far = min(min(min(hi.x, hi.y), hi.z), tmax);
    if near <= far { return near; }
    return RT_F32_MAX;
}

// Watertight ray/triangle test (Woop, Benthin, Wald 2013), in two parts:
// the per-ray shear (rt_shear: the axes, x and y the shear plane, z the
// dominant axis) and the test of one triangle with it (rt_watertight).
// rt_triangle runs both for one triangle; the lean loop of traverse.wgsl
// computes the shear once per ray.
struct RtShear {
    k: vec3<u32>,
    s: vec3<f32>,
    ok: bool,
}

fn rt_shear(d: vec3<f32>) -> RtShear {
    let ad = abs(d);
    var kz = 2u;
    if ad.x > ad.y {
        if ad.x > ad.z { kz = 0u; }
    } else if ad.y > ad.z {
        kz = 1u;
    }
    var kx = (kz + 1u) % 3u;
    var ky = (kx + 1u) % 3u;
    if d[kz] < 0.0 {
        let tmp = kx;
        kx = ky;
        ky = tmp;
    }
    return RtShear(vec3<u32>(kx, ky, kz), vec3<f32>(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]), d[kz] != 0.0);
}

// Triangle (a, b, c) against the ray from o with its direction's shear: t
// (-1.0 on a miss); on a hit, the weights of vertices 1 and 2 in *bary. A
// triangle with NaN vertices is never hit (every comparison fails).
fn rt_watertight(a: vec3<f32>, b: vec3<f32>, c: vec3<f32>, o: vec3<f32>, sh: RtShear, tmin: f32, tmax: f32, bary: ptr<function, vec2<f32>>) -> f32 {
    let pa = a - o;
    let pb = b - o;
    let pc = c - o;
    let kx = sh.k.x;
    let ky = sh.k.y;
    let kz = sh.k.z;
    let ax = pa[kx] - sh.s.x * pa[kz];
    let ay = pa[ky] - sh.s.y * pa[kz];
    let bx = pb[kx] - sh.s.x * pb[kz];
    let by = pb[ky] - sh.s.y * pb[kz];
    let cx = pc[kx] - sh.s.x * pc[kz];
    let cy = pc[ky] - sh.s.y * pc[kz];
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) { return -1.0; }
    let det = u + v + w;
    if det == 0.0 { return -1.0; }
    let sz = sh.s.z;
    let t = (u * sz * pa[kz] + v * sz * pb[kz] + w * sz * pc[kz]) / det;
    if !(t > tmin && t < tmax) { return -1.0; }
    *bary = vec2<f32>(v / det, w / det);
    return t;
}

// Whether the ray along d meets triangle (a, b, c) on its counter-clockwise
// side (asked only where culling needs it).
fn rt_front(a: vec3<f32>, b: vec3<f32>, c: vec3<f32>, d: vec3<f32>) -> bool {
    return dot(d, cross(b - a, c - a)) < 0.0;
}

// The watertight test of one triangle: t (or a negative value on a miss);
// on a hit, rt_c_bary gets the weights of vertices 1 and 2 and rt_tri_front
// whether the ray hits the counter-clockwise side.
var<private> rt_tri_front: bool;
fn rt_triangle(a: vec3<f32>, b: vec3<f32>, c: vec3<f32>, r: RtRay, tmax: f32) -> f32 {
    let sh = rt_shear(r.direction);
    if !sh.ok { return -1.0; }
    var bary = rt_c_bary;
    let t = rt_watertight(a, b, c, r.origin, sh, r.tmin, tmax, &bary);
    rt_c_bary = bary;
    rt_tri_front = rt_front(a, b, c, r.direction);
    return t;
}

// The hit kind (rt_hk) of a hit on primitive prim of geometry instance gi
// by a ray along world direction d, w2o the instance's world to object: a
// triangle's side as rt_front says in object space, or 3 for custom ones.
fn rt_hit_kind(custom: bool, gi: u32, prim: u32, w2o: mat4x4<f32>, d: vec3<f32>) -> u32 {
    if custom { return 3u; }
    let g = rt_scene[2] + gi * 8u;
    let ib = rt_scene[g + 2u] + prim * 3u;
    let a = rt_tri_corner(g, rt_scene[ib]);
    let b = rt_tri_corner(g, rt_scene[ib + 1u]);
    let c = rt_tri_corner(g, rt_scene[ib + 2u]);
    if rt_front(a, b, c, (w2o * vec4<f32>(d, 0.0)).xyz) { return 1u; }
    return 2u;
}

// The segment of n keys (at least 2) spread evenly over [t0, t1] that the
// current ray's time falls in, and the fraction along it: rt-runtime's
// motion::segment step by step.
fn rt_motion_segment(n: u32, t0: f32, t1: f32) -> vec2<f32> {
    let last = f32(n - 1u);
    var u = 0.0;
    if t1 > t0 {
        u = clamp((rt_time - t0) / (t1 - t0), 0.0, 1.0) * last;
    } else if rt_time > t0 {
        u = last;
    }
    // A NaN time clamps to NaN: the first key.
    if u != u {
        u = 0.0;
    }
    let i = min(u32(floor(u)), n - 2u);
    return vec2<f32>(f32(i), u - f32(i));
}

// Vertex v of the triangle geometry at instance-table word g, at the
// current ray's time: its position (kind 0), or (kind 2, vertex motion)
// its keys [key count, vertex count, t0, t1, positions per key]
// interpolated as rt-runtime's VertexMotion::triangle_at.
fn rt_tri_corner(g: u32, v: u32) -> vec3<f32> {
    let pb = rt_scene[g + 1u];
    if rt_scene[g] != 2u {
        return rt_v3(pb + v * 3u);
    }
    let s = rt_motion_segment(rt_scene[pb], rt_f(pb + 2u), rt_f(pb + 3u));
    let a = pb + 4u + (u32(s.x) * rt_scene[pb + 1u] + v) * 3u;
    let b = a + rt_scene[pb + 1u] * 3u;
    return rt_v3(a) * (1.0 - s.y) + rt_v3(b) * s.y;
}

fn rt_load_object(w: u32) -> u32 { return rt_hw(w); }
