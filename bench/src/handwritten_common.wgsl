// The hand-written baseline kernels' common part: primary ray + one
// ambient-occlusion ray per hit, no programs, no dispatch. Each tree's file
// (handwritten.wgsl: BVH2, handwritten_cwbvh.wgsl: CWBVH) follows it with
// its nodes' binding and `closest`, which sets `hit_prim`.
struct Camera {
    eye: vec4<f32>,
    u: vec4<f32>,
    v: vec4<f32>,
    w: vec4<f32>,
    dim: vec4<u32>,
}
// Triangles in the tree's primitive order (9 floats each).
@group(0) @binding(1) var<storage, read> tris: array<f32>;
@group(0) @binding(2) var<storage, read_write> out: array<f32>;
@group(0) @binding(3) var<uniform> cam: Camera;

const FAR: f32 = 0x1.fffffep+127f;

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
