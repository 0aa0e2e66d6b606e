// The baseline kernel's traversal over obvhs's compressed wide BVH (CWBVH,
// Ylitie et al. 2017; after handwritten_common.wgsl), as the megakernel
// walks it for this workload: the same rays and the same triangle test as
// the BVH2 variant (handwritten.wgsl); only the traversal differs.
// Nodes: 20 words each, obvhs's `CwBvhNode` as it lies in memory:
// p (3 f32), e0 e1 e2 imask (bytes), child base, primitive base, then
// 8-byte arrays of child meta, min x, max x, min y, max y, min z, max z.
@group(0) @binding(0) var<storage, read> nodes: array<u32>;

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
