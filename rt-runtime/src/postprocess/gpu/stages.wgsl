// The post-processing stages on the device: the passes of
// `postprocess/denoise.rs` (prepare, a-trous, finish) and of
// `postprocess/tonemap.rs`, the same arithmetic as those CPU references,
// one entry point a pass over one pixel an invocation. `postprocess/gpu.rs`
// binds the buffers of each pass and dispatches them in order. A pass
// runs over the top-left `width` x `height` of its images, each in rows
// of its own length (`strides`: a buffer larger than the run); `src` and
// `dst` are the run's own, in rows of `width`.

struct Params {
    width: u32,
    height: u32,
    // The a-trous pass's tap spacing.
    step: i32,
    variance_radius: i32,
    sigma_luminance: f32,
    sigma_normal: f32,
    sigma_albedo: f32,
    // `blend` for the denoiser's finish, `exposure` for the tonemapper.
    blend_or_exposure: f32,
    gamma: f32,
    // 1 where `variance` holds the renderer's per-pixel variance.
    has_variance: u32,
    // The row lengths of `color`, `albedo`, `normal` and `variance`.
    strides: vec4<u32>,
}

@group(0) @binding(0) var<uniform> params: Params;
// The stage's input (colour) and the denoiser's guides.
@group(0) @binding(1) var<storage, read> color: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> albedo: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> normal: array<vec4<f32>>;
// The previous pass's light (rgb) and variance (a).
@group(0) @binding(4) var<storage, read> src: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> dst: array<vec4<f32>>;
// The denoiser's per-pixel variance (x; negative where unknown), read
// where `params.has_variance` is 1.
@group(0) @binding(6) var<storage, read> variance: array<vec4<f32>>;

const ALBEDO_FLOOR: f32 = 1e-3;
const KERNEL: array<f32, 5> = array<f32, 5>(1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);

fn luminance(c: vec3<f32>) -> f32 {
    return dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
}

fn demodulation(x: i32, y: i32) -> vec3<f32> {
    let a = albedo[u32(y) * params.strides.y + u32(x)].xyz;
    return select(vec3<f32>(1.0), a, a > vec3<f32>(ALBEDO_FLOOR));
}

fn unit_normal(x: i32, y: i32) -> vec3<f32> {
    let n = normal[u32(y) * params.strides.z + u32(x)].xyz;
    let len = length(n);
    if len > 0.0 {
        return n / len;
    }
    return vec3<f32>(0.0);
}

fn normal_weight(a: vec3<f32>, b: vec3<f32>) -> f32 {
    if all(a == b) {
        return 1.0;
    }
    return pow(max(dot(a, b), 0.0), params.sigma_normal);
}

fn albedo_weight(a: vec3<f32>, b: vec3<f32>) -> f32 {
    if all(a == b) {
        return 1.0;
    }
    let d = a - b;
    return exp(-dot(d, d) / params.sigma_albedo);
}

fn inside(x: i32, y: i32) -> bool {
    return x >= 0 && y >= 0 && x < i32(params.width) && y < i32(params.height);
}

// The run's own index of pixel (x, y): of `src` and `dst`.
fn index(x: i32, y: i32) -> u32 {
    return u32(y) * params.width + u32(x);
}

fn color_at(x: i32, y: i32) -> vec4<f32> {
    return color[u32(y) * params.strides.x + u32(x)];
}

// Pass 1: the demodulated colour and its luminance's variance: the
// given one, or else the spatial estimate.
@compute @workgroup_size(8, 8)
fn prepare(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let x = i32(id.x);
    let y = i32(id.y);
    let p = index(x, y);
    if params.has_variance == 1u {
        let given = variance[u32(y) * params.strides.w + u32(x)].x;
        if given >= 0.0 {
            dst[p] = vec4<f32>(color_at(x, y).xyz / demodulation(x, y), given);
            return;
        }
    }
    let np = unit_normal(x, y);
    var m1 = 0.0;
    var m2 = 0.0;
    var sum = 0.0;
    let r = params.variance_radius;
    for (var dy = -r; dy <= r; dy++) {
        for (var dx = -r; dx <= r; dx++) {
            let qx = x + dx;
            let qy = y + dy;
            if !inside(qx, qy) {
                continue;
            }
            let q = index(qx, qy);
            var weight = 1.0;
            if q != p {
                weight = normal_weight(np, unit_normal(qx, qy));
            }
            let l = luminance(color_at(qx, qy).xyz / demodulation(qx, qy));
            m1 += weight * l;
            m2 += weight * l * l;
            sum += weight;
        }
    }
    m1 /= sum;
    m2 /= sum;
    dst[p] = vec4<f32>(color_at(x, y).xyz / demodulation(x, y), max(m2 - m1 * m1, 0.0));
}

fn blurred_variance(x: i32, y: i32) -> f32 {
    var g = array<f32, 3>(0.25, 0.5, 0.25);
    var v = 0.0;
    var sum = 0.0;
    for (var j = 0; j < 3; j++) {
        for (var i = 0; i < 3; i++) {
            let qx = x + i - 1;
            let qy = y + j - 1;
            if inside(qx, qy) {
                v += g[i] * g[j] * src[index(qx, qy)].w;
                sum += g[i] * g[j];
            }
        }
    }
    return v / sum;
}

// Pass 2, repeated: one a-trous step, `src` into `dst`.
@compute @workgroup_size(8, 8)
fn atrous(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let x = i32(id.x);
    let y = i32(id.y);
    let p = index(x, y);
    let center = src[p];
    let sigma = params.sigma_luminance * sqrt(blurred_variance(x, y)) + 1e-6;
    let lp = luminance(center.xyz);
    let np = unit_normal(x, y);
    let ap = demodulation(x, y);
    var kernel = KERNEL;
    var c = vec3<f32>(0.0);
    var variance = 0.0;
    var sum = 0.0;
    for (var j = 0; j < 5; j++) {
        for (var i = 0; i < 5; i++) {
            let qx = x + (i - 2) * params.step;
            let qy = y + (j - 2) * params.step;
            if !inside(qx, qy) {
                continue;
            }
            let q = index(qx, qy);
            let s = src[q];
            var weight = kernel[i] * kernel[j];
            if q != p {
                let wl = exp(-abs(lp - luminance(s.xyz)) / sigma);
                weight = weight * wl * normal_weight(np, unit_normal(qx, qy)) * albedo_weight(ap, demodulation(qx, qy));
            }
            c += weight * s.xyz;
            variance += weight * weight * s.w;
            sum += weight;
        }
    }
    dst[p] = vec4<f32>(c / sum, variance / (sum * sum));
}

// Pass 3: the filtered light times the albedo, blended with the input.
@compute @workgroup_size(8, 8)
fn finish(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let x = i32(id.x);
    let y = i32(id.y);
    let p = index(x, y);
    let input = color_at(x, y);
    let filtered = src[p].xyz * demodulation(x, y);
    dst[p] = vec4<f32>(mix(input.xyz, filtered, 1.0 - params.blend_or_exposure), input.w);
}

fn aces_fitted(v: f32) -> f32 {
    let x = max(v, 0.0);
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// The tonemapper: exposure, the ACES-fitted curve, gamma.
@compute @workgroup_size(8, 8)
fn tonemap(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let p = index(i32(id.x), i32(id.y));
    let c = color_at(i32(id.x), i32(id.y));
    let inv_gamma = 1.0 / max(params.gamma, 1e-3);
    let e = c.xyz * params.blend_or_exposure;
    let mapped = vec3<f32>(
        pow(aces_fitted(e.x), inv_gamma),
        pow(aces_fitted(e.y), inv_gamma),
        pow(aces_fitted(e.z), inv_gamma),
    );
    dst[p] = vec4<f32>(mapped, c.w);
}
