// The temporal denoiser's pass on the device: the arithmetic of
// `postprocess/temporal.rs` (reprojection, rejection, blending), one
// invocation a pixel. It writes `next`, of `width * height` pixels `n`:
// the next history (four texels a pixel, as `previous`), then the
// accumulated colour (n texels) and its variance (n), which
// `postprocess/gpu.rs` copies out for the spatial passes of
// `stages.wgsl` (six storage buffers is as many as every device binds).
// The frame's images are read over their top-left `width` x `height`, each
// in rows of its own length (`strides`); `previous` and `next` are the
// run's own.

struct Params {
    width: u32,
    height: u32,
    // 1 where `previous` holds a history of this size.
    has_history: u32,
    alpha_min: f32,
    // The row lengths of `color`, `albedo`, `normal` and `position`.
    strides: vec4<u32>,
    // The frame's camera eye (xyz).
    eye: vec4<f32>,
    // The history's camera (xyz each).
    prev_eye: vec4<f32>,
    prev_u: vec4<f32>,
    prev_v: vec4<f32>,
    prev_w: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> color: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> albedo: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> normal: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> position: array<vec4<f32>>;
// The last run's history, four texels a pixel: colour and frames,
// moments, unit normal, position.
@group(0) @binding(5) var<storage, read> previous: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read_write> next: array<vec4<f32>>;

const ALBEDO_FLOOR: f32 = 1e-3;
const NORMAL_AGREEMENT: f32 = 0.9;
const PLANE_TOLERANCE: f32 = 0.02;
const VARIANCE_FRAMES: f32 = 4.0;
const MAX_FRAMES: f32 = 256.0;

fn luminance(c: vec3<f32>) -> f32 {
    return dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
}

fn unit(n: vec3<f32>) -> vec3<f32> {
    let len = length(n);
    if len > 0.0 {
        return n / len;
    }
    return vec3<f32>(0.0);
}

// The history's texel index of the pixel where `p` appeared, or -1.
fn reprojected(p: vec3<f32>) -> i32 {
    let d = p - params.prev_eye.xyz;
    let w = params.prev_w.xyz;
    let depth = dot(d, w) / dot(w, w);
    // Not in front of the camera, or not finite (NaN fails both sides).
    if !(depth > 0.0) || !(depth < 3.0e38) {
        return -1;
    }
    let u = params.prev_u.xyz;
    let v = params.prev_v.xyz;
    let screen = vec2<f32>(dot(d, u) / dot(u, u), dot(d, v) / dot(v, v)) / depth;
    let size = vec2<f32>(f32(params.width), f32(params.height));
    let px = (screen + 1.0) * 0.5 * size;
    if !(px.x >= 0.0 && px.y >= 0.0 && px.x < size.x && px.y < size.y) {
        return -1;
    }
    return i32(u32(px.y) * params.width + u32(px.x));
}

@compute @workgroup_size(8, 8)
fn temporal(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let p = id.y * params.width + id.x;
    let c = color[id.y * params.strides.x + id.x];
    let n = unit(normal[id.y * params.strides.z + id.x].xyz);
    let pos = position[id.y * params.strides.w + id.x];
    let hit = pos.w > 0.0;
    let world = pos.xyz / pos.w;
    let a = albedo[id.y * params.strides.y + id.x].xyz;
    let l = luminance(c.xyz / select(vec3<f32>(1.0), a, a > vec3<f32>(ALBEDO_FLOOR)));
    var acc = c.xyz;
    var moments = vec2<f32>(l, l * l);
    var frames = 1.0;
    var alpha = 1.0;
    if params.has_history == 1u && hit {
        let q = reprojected(world);
        if q >= 0 {
            let t = u32(q) * 4u;
            let old_color = previous[t];
            let old_moments = previous[t + 1u];
            let old_normal = previous[t + 2u].xyz;
            let old_position = previous[t + 3u];
            let tolerance = PLANE_TOLERANCE * length(world - params.eye.xyz);
            let same = old_color.w >= 1.0 && old_position.w > 0.0 && dot(n, old_normal) >= NORMAL_AGREEMENT
                && abs(dot(old_position.xyz - world, n)) <= tolerance;
            if same {
                frames = min(old_color.w + 1.0, MAX_FRAMES);
                alpha = max(params.alpha_min, 1.0 / frames);
                acc = mix(old_color.xyz, c.xyz, alpha);
                moments = mix(old_moments.xy, vec2<f32>(l, l * l), alpha);
            }
        }
    }
    var variance = -1.0;
    if frames >= VARIANCE_FRAMES {
        variance = max(moments.y - moments.x * moments.x, 0.0) * alpha;
    }
    let pixels = params.width * params.height;
    next[pixels * 4u + p] = vec4<f32>(acc, c.w);
    next[pixels * 5u + p] = vec4<f32>(variance, 0.0, 0.0, 0.0);
    next[p * 4u] = vec4<f32>(acc, frames);
    next[p * 4u + 1u] = vec4<f32>(moments, 0.0, 0.0);
    next[p * 4u + 2u] = vec4<f32>(n, 0.0);
    var stored = vec4<f32>(0.0);
    if hit {
        stored = vec4<f32>(world, 1.0);
    }
    next[p * 4u + 3u] = stored;
}
