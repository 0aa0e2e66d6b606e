// The baseline kernel's traversal over a BVH2 (after
// handwritten_common.wgsl). Same BVH, same rays as the megakernel's BVH2
// search.
// Nodes as two arrays, so each binding stays under lavapipe's 128 MiB on the
// 2M-triangle scene: six bounds per node, and (count, first, primitive).
@group(0) @binding(0) var<storage, read> bounds: array<f32>;
@group(0) @binding(4) var<storage, read> links: array<u32>;

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
