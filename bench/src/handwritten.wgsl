// The baseline kernel: primary ray + one ambient-occlusion ray per hit over
// a BVH2, no programs, no dispatch. Same BVH, same rays as the megakernel.
struct Camera {
    eye: vec4<f32>,
    u: vec4<f32>,
    v: vec4<f32>,
    w: vec4<f32>,
    dim: vec4<u32>,
}
// Nodes as two arrays, so each binding stays under lavapipe's 128 MiB on the
// 2M-triangle scene: six bounds per node, and (count, first, primitive).
@group(0) @binding(0) var<storage, read> bounds: array<f32>;
@group(0) @binding(1) var<storage, read> tris: array<f32>;
@group(0) @binding(2) var<storage, read_write> out: array<f32>;
@group(0) @binding(3) var<uniform> cam: Camera;
@group(0) @binding(4) var<storage, read> links: array<u32>;

const FAR: f32 = 3.40282347e38;

// Node `i`'s box against a ray; its entry distance or FAR.
fn aabb_hit(i: u32, o: vec3<f32>, inv: vec3<f32>, tmin: f32, tmax: f32) -> f32 {
    let n = i * 6u;
    let lo = vec3<f32>(bounds[n], bounds[n + 1u], bounds[n + 2u]);
    let hi = vec3<f32>(bounds[n + 3u], bounds[n + 4u], bounds[n + 5u]);
    let t0 = (lo - o) * inv;
    let t1 = (hi - o) * inv;
    let near = max(max(max(min(t0.x, t1.x), min(t0.y, t1.y)), min(t0.z, t1.z)), tmin);
    let far = min(min(min(max(t0.x, t1.x), max(t0.y, t1.y)), max(t0.z, t1.z)), tmax);
    if near <= far { return near; }
    return FAR;
}

// Moeller-Trumbore; returns t or FAR.
fn triangle(i: u32, o: vec3<f32>, d: vec3<f32>, tmin: f32, tmax: f32) -> f32 {
    let b = i * 9u;
    let a = vec3<f32>(tris[b], tris[b + 1u], tris[b + 2u]);
    let e1 = vec3<f32>(tris[b + 3u], tris[b + 4u], tris[b + 5u]) - a;
    let e2 = vec3<f32>(tris[b + 6u], tris[b + 7u], tris[b + 8u]) - a;
    let p = cross(d, e2);
    let det = dot(e1, p);
    if abs(det) < 1e-12 { return FAR; }
    let inv = 1.0 / det;
    let s = o - a;
    let u = dot(s, p) * inv;
    if u < 0.0 || u > 1.0 { return FAR; }
    let q = cross(s, e1);
    let v = dot(d, q) * inv;
    if v < 0.0 || u + v > 1.0 { return FAR; }
    let t = dot(e2, q) * inv;
    if t > tmin && t < tmax { return t; }
    return FAR;
}

var<private> hit_prim: u32;

fn closest(o: vec3<f32>, d: vec3<f32>, tmin: f32) -> f32 {
    let inv = 1.0 / d;
    var tmax = FAR;
    hit_prim = 0xffffffffu;
    var stack: array<u32, 64>;
    var sp = 0u;
    if aabb_hit(0u, o, inv, tmin, tmax) == FAR { return FAR; }
    stack[0] = 0u;
    sp = 1u;
    while sp > 0u {
        sp -= 1u;
        let n = stack[sp] * 3u;
        let count = links[n];
        let first = links[n + 1u];
        if count > 0u {
            for (var k = first; k < first + count; k++) {
                let prim = links[n + 2u];
                let t = triangle(prim, o, d, tmin, tmax);
                if t < tmax {
                    tmax = t;
                    hit_prim = prim;
                }
            }
            continue;
        }
        let ta = aabb_hit(first, o, inv, tmin, tmax);
        let tb = aabb_hit(first + 1u, o, inv, tmin, tmax);
        var near = first;
        var far = first + 1u;
        var tn = ta;
        var tf = tb;
        if tb < ta {
            near = first + 1u;
            far = first;
            tn = tb;
            tf = ta;
        }
        if tf != FAR && sp < 64u { stack[sp] = far; sp += 1u; }
        if tn != FAR && sp < 64u { stack[sp] = near; sp += 1u; }
    }
    return tmax;
}

fn hash(x: u32) -> u32 {
    let state = x * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let dim = cam.dim.xy;
    if gid.x >= dim.x || gid.y >= dim.y { return; }
    let p = (vec2<f32>(gid.xy) + 0.5) / vec2<f32>(dim) * 2.0 - 1.0;
    let d = normalize(p.x * cam.u.xyz + p.y * cam.v.xyz + cam.w.xyz);
    let t = closest(cam.eye.xyz, d, 1e-4);
    var value = 0.0;
    if t < FAR {
        let b = hit_prim * 9u;
        let a = vec3<f32>(tris[b], tris[b + 1u], tris[b + 2u]);
        var n = normalize(cross(vec3<f32>(tris[b + 3u], tris[b + 4u], tris[b + 5u]) - a, vec3<f32>(tris[b + 6u], tris[b + 7u], tris[b + 8u]) - a));
        n = faceForward(n, d, n);
        let h1 = hash(gid.x + gid.y * dim.x);
        let h2 = hash(h1);
        let u1 = f32(h1 >> 8u) / 16777216.0;
        let u2 = f32(h2 >> 8u) / 16777216.0;
        let r = sqrt(u1);
        let phi = 6.2831855 * u2;
        var axis = vec3<f32>(1.0, 0.0, 0.0);
        if abs(n.x) > 0.9 { axis = vec3<f32>(0.0, 1.0, 0.0); }
        let tt = normalize(cross(n, axis));
        let bb = cross(n, tt);
        let ao = normalize(tt * (r * cos(phi)) + bb * (r * sin(phi)) + n * sqrt(max(1.0 - u1, 0.0)));
        let origin = cam.eye.xyz + t * d + n * 1e-4;
        value = select(1.0, 0.0, closest(origin, ao, 0.0) < FAR);
        out[dim.x * dim.y + gid.y * dim.x + gid.x] = 1.0;
    }
    out[gid.y * dim.x + gid.x] = value;
}
