// The hand-written kernel over obvhs's compressed wide BVH (CWBVH, Ylitie et
// al. 2017), as the megakernel walks it for this workload: the same rays
// and the same triangle test as handwritten.wgsl (the BVH2 variant); only
// the traversal differs.
struct Camera {
    eye: vec4<f32>,
    u: vec4<f32>,
    v: vec4<f32>,
    w: vec4<f32>,
    dim: vec4<u32>,
}
// Nodes: 20 words each, obvhs's `CwBvhNode` as it lies in memory:
// p (3 f32), e0 e1 e2 imask (bytes), child base, primitive base, then
// 8-byte arrays of child cm, min x, max x, min y, max y, min z, max z.
@group(0) @binding(0) var<storage, read> nodes: array<u32>;
// Triangles in the CWBVH's primitive order (9 floats each).
@group(0) @binding(1) var<storage, read> tris: array<f32>;
@group(0) @binding(2) var<storage, read_write> out: array<f32>;
@group(0) @binding(3) var<uniform> cam: Camera;

const FAR: f32 = 3.40282347e38;

// Moeller-Trumbore; returns t or FAR (as handwritten.wgsl).
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

// Byte `i` (0-3) of a word, as a float.
fn byte_f(w: u32, i: u32) -> f32 {
    return f32((w >> (i * 8u)) & 0xffu);
}

// The children of node `n` the ray segment enters: internal children as
// bits 24-31 (at the slot the ray octant orders them to), leaf children as
// their triangles' bits 0-23.
fn node_hits(n: u32, o: vec3<f32>, inv: vec3<f32>, oct_inv4: u32, tmin: f32, tmax: f32) -> u32 {
    let b = n * 20u;
    let p = vec3<f32>(bitcast<f32>(nodes[b]), bitcast<f32>(nodes[b + 1u]), bitcast<f32>(nodes[b + 2u]));
    let ew = nodes[b + 3u];
    // The node's scale per axis: a power of two with the stored exponent.
    let e = vec3<f32>(
        bitcast<f32>((ew & 0xffu) << 23u),
        bitcast<f32>(((ew >> 8u) & 0xffu) << 23u),
        bitcast<f32>(((ew >> 16u) & 0xffu) << 23u),
    );
    let scale = e * inv;
    let shift = (p - o) * inv;
    var hits = 0u;
    for (var half = 0u; half < 2u; half++) {
        let cm = nodes[b + 6u + half];
        // Per byte: internal children have cm 24-31 (bits 3 and 4 set);
        // their bit index is their slot in the ray octant's order, a leaf's
        // is its first triangle; child bits are 1 for an internal child,
        // the unary triangle count for a leaf.
        let inner = ((cm & (cm << 1u)) & 0x10101010u) >> 4u;
        let index4 = (cm ^ (oct_inv4 & (inner * 0xffu))) & 0x1f1f1f1fu;
        let bits4 = (cm >> 5u) & 0x07070707u;
        let lox = nodes[b + 8u + half];
        let hix = nodes[b + 10u + half];
        let loy = nodes[b + 12u + half];
        let hiy = nodes[b + 14u + half];
        let loz = nodes[b + 16u + half];
        let hiz = nodes[b + 18u + half];
        for (var i = 0u; i < 4u; i++) {
            let t0 = vec3<f32>(byte_f(lox, i), byte_f(loy, i), byte_f(loz, i)) * scale + shift;
            let t1 = vec3<f32>(byte_f(hix, i), byte_f(hiy, i), byte_f(hiz, i)) * scale + shift;
            let lo = min(t0, t1);
            let hi = max(t0, t1);
            let near = max(max(max(lo.x, lo.y), lo.z), tmin);
            let far = min(min(min(hi.x, hi.y), hi.z), tmax);
            if near <= far {
                let sh = i * 8u;
                hits |= ((bits4 >> sh) & 0xffu) << ((index4 >> sh) & 0xffu);
            }
        }
    }
    return hits;
}

var<private> hit_prim: u32;

fn closest(o: vec3<f32>, d: vec3<f32>, tmin: f32) -> f32 {
    let inv = 1.0 / d;
    let oct_inv4 = select(0x04040404u, 0u, d.x < 0.0) | select(0x02020202u, 0u, d.y < 0.0)
        | select(0x01010101u, 0u, d.z < 0.0);
    var tmax = FAR;
    hit_prim = 0xffffffffu;
    // Groups of (first child node, hit bits 24-31 | imask bits 0-7) and of
    // (first triangle, triangle bits).
    var stack: array<vec2<u32>, 32>;
    var sp = 0u;
    var nodes_left = vec2<u32>(0u, 0x80000000u);
    var tris_left = vec2<u32>(0u, 0u);
    loop {
        while tris_left.y != 0u {
            let k = firstLeadingBit(tris_left.y);
            tris_left.y &= ~(1u << k);
            let id = tris_left.x + k;
            let t = triangle(id, o, d, tmin, tmax);
            if t < tmax {
                tmax = t;
                hit_prim = id;
            }
        }
        if (nodes_left.y & 0xff000000u) != 0u {
            let mask = nodes_left.y;
            let bit = firstLeadingBit(mask);
            nodes_left.y &= ~(1u << bit);
            if (nodes_left.y & 0xff000000u) != 0u && sp < 32u {
                stack[sp] = nodes_left;
                sp += 1u;
            }
            // The child's slot, and its rank among the internal children.
            let slot = (bit - 24u) ^ (oct_inv4 & 0xffu);
            let n = nodes_left.x + countOneBits(mask & ~(0xffffffffu << slot));
            let hits = node_hits(n, o, inv, oct_inv4, tmin, tmax);
            nodes_left = vec2<u32>(nodes[n * 20u + 4u], (hits & 0xff000000u) | (nodes[n * 20u + 3u] >> 24u));
            tris_left = vec2<u32>(nodes[n * 20u + 5u], hits & 0x00ffffffu);
        } else {
            nodes_left = vec2<u32>(0u, 0u);
        }
        if tris_left.y == 0u && (nodes_left.y & 0xff000000u) == 0u {
            if sp == 0u {
                break;
            }
            sp -= 1u;
            nodes_left = stack[sp];
        }
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
