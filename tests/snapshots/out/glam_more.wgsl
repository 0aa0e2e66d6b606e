// ray_generation program `glam_more`

fn rt_any_orthonormal_vector(v: vec3<f32>) -> vec3<f32> {
    let sign = select(1.0f, -1.0f, (bitcast<u32>(v.z) & 0x80000000u) != 0u);
    let a = -1.0f / (sign + v.z);
    let b = v.x * v.y * a;
    return vec3<f32>(b, sign + v.y * v.y * a, -v.y);
}

fn rt_bufload_vec3f(b: RtBuffer, i: u32) -> vec3<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec3f(b.offset + i * 3u);
    }
    return vec3<f32>();
}

fn rt_bufload_vec4f(b: RtBuffer, i: u32) -> vec4<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec4f(b.offset + i * 4u);
    }
    return vec4<f32>();
}

fn rt_bufstore_vec4f(b: RtBuffer, i: u32, v: vec4<f32>) {
    if rt_buf_check(b, i) {
        rt_store_vec4f(b.offset + i * 4u, v);
    }
}

fn rt_fmod(x: f32, y: f32) -> f32 {
    let ux = bitcast<u32>(x);
    let uy = bitcast<u32>(y);
    var ex = i32((ux >> 23u) & 0xffu);
    var ey = i32((uy >> 23u) & 0xffu);
    let sx = ux & 0x80000000u;
    if (uy << 1u) == 0u || ex == 0xff || (uy & 0x7fffffffu) > 0x7f800000u {
        return x % y;
    }
    if (ux << 1u) <= (uy << 1u) {
        if (ux << 1u) == (uy << 1u) {
            return bitcast<f32>(sx);
        }
        return x;
    }
    var mx = (ux & 0x007fffffu) | 0x00800000u;
    if ex == 0 {
        var i = ux << 9u;
        while (i >> 31u) == 0u {
            ex -= 1;
            i <<= 1u;
        }
        mx = ux << u32(1 - ex);
    }
    var my = (uy & 0x007fffffu) | 0x00800000u;
    if ey == 0 {
        var i = uy << 9u;
        while (i >> 31u) == 0u {
            ey -= 1;
            i <<= 1u;
        }
        my = uy << u32(1 - ey);
    }
    loop {
        let i = mx - my;
        if (i >> 31u) == 0u {
            if i == 0u {
                return bitcast<f32>(sx);
            }
            mx = i;
        }
        if ex <= ey {
            break;
        }
        mx <<= 1u;
        ex -= 1;
    }
    while (mx >> 23u) == 0u {
        mx <<= 1u;
        ex -= 1;
    }
    if ex > 0 {
        mx = (mx - 0x00800000u) | (u32(ex) << 23u);
    } else {
        mx >>= u32(1 - ex);
    }
    return bitcast<f32>(mx | sx);
}

fn rt_inverse3(m: mat3x3<f32>) -> mat3x3<f32> {
    let tmp0 = cross(m[1], m[2]);
    let tmp1 = cross(m[2], m[0]);
    let tmp2 = cross(m[0], m[1]);
    let inv_det = vec3<f32>(1.0f / dot(m[0], tmp0));
    return transpose(mat3x3<f32>(tmp0 * inv_det, tmp1 * inv_det, tmp2 * inv_det));
}

fn rt_inverse4(m: mat4x4<f32>) -> mat4x4<f32> {
    let m00 = m[0].x; let m01 = m[0].y; let m02 = m[0].z; let m03 = m[0].w;
    let m10 = m[1].x; let m11 = m[1].y; let m12 = m[1].z; let m13 = m[1].w;
    let m20 = m[2].x; let m21 = m[2].y; let m22 = m[2].z; let m23 = m[2].w;
    let m30 = m[3].x; let m31 = m[3].y; let m32 = m[3].z; let m33 = m[3].w;
    let coef00 = m22 * m33 - m32 * m23;
    let coef02 = m12 * m33 - m32 * m13;
    let coef03 = m12 * m23 - m22 * m13;
    let coef04 = m21 * m33 - m31 * m23;
    let coef06 = m11 * m33 - m31 * m13;
    let coef07 = m11 * m23 - m21 * m13;
    let coef08 = m21 * m32 - m31 * m22;
    let coef10 = m11 * m32 - m31 * m12;
    let coef11 = m11 * m22 - m21 * m12;
    let coef12 = m20 * m33 - m30 * m23;
    let coef14 = m10 * m33 - m30 * m13;
    let coef15 = m10 * m23 - m20 * m13;
    let coef16 = m20 * m32 - m30 * m22;
    let coef18 = m10 * m32 - m30 * m12;
    let coef19 = m10 * m22 - m20 * m12;
    let coef20 = m20 * m31 - m30 * m21;
    let coef22 = m10 * m31 - m30 * m11;
    let coef23 = m10 * m21 - m20 * m11;
    let fac0 = vec4<f32>(coef00, coef00, coef02, coef03);
    let fac1 = vec4<f32>(coef04, coef04, coef06, coef07);
    let fac2 = vec4<f32>(coef08, coef08, coef10, coef11);
    let fac3 = vec4<f32>(coef12, coef12, coef14, coef15);
    let fac4 = vec4<f32>(coef16, coef16, coef18, coef19);
    let fac5 = vec4<f32>(coef20, coef20, coef22, coef23);
    let vec0 = vec4<f32>(m10, m00, m00, m00);
    let vec1 = vec4<f32>(m11, m01, m01, m01);
    let vec2_ = vec4<f32>(m12, m02, m02, m02);
    let vec3_ = vec4<f32>(m13, m03, m03, m03);
    let inv0 = vec1 * fac0 - vec2_ * fac1 + vec3_ * fac2;
    let inv1 = vec0 * fac0 - vec2_ * fac3 + vec3_ * fac4;
    let inv2 = vec0 * fac1 - vec1 * fac3 + vec3_ * fac5;
    let inv3 = vec0 * fac2 - vec1 * fac4 + vec2_ * fac5;
    let sign_a = vec4<f32>(1.0f, -1.0f, 1.0f, -1.0f);
    let sign_b = vec4<f32>(-1.0f, 1.0f, -1.0f, 1.0f);
    let inverse = mat4x4<f32>(inv0 * sign_a, inv1 * sign_b, inv2 * sign_a, inv3 * sign_b);
    let col0 = vec4<f32>(inverse[0].x, inverse[1].x, inverse[2].x, inverse[3].x);
    let dot0 = m[0] * col0;
    let dot1 = dot0.x + dot0.y + dot0.z + dot0.w;
    return inverse * (1.0f / dot1);
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_mat4(w: u32) -> mat4x4<f32> {
    return mat4x4<f32>(rt_load_vec4f(w + 0u), rt_load_vec4f(w + 4u), rt_load_vec4f(w + 8u), rt_load_vec4f(w + 12u));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_rem_euclid(a: f32, b: f32) -> f32 {
    let r = rt_fmod(a, b);
    return select(r, r + abs(b), r < 0.0f);
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

fn rtp_glam_more(to_world: mat4x4<f32>, normals: RtBuffer, out: RtBuffer) {
    var out_1 = out;
    let i: u32 = rt_launch_index().x;
    let n: vec3<f32> = normalize(rt_bufload_vec3f(normals, i));
    var to_object: mat4x4<f32> = rt_inverse4(to_world);
    let tangent: vec3<f32> = rt_any_orthonormal_vector(n);
    let tmp = vec3<f32>(1.0f, 2.0f, 3.0f);
    let tmp_1 = (tmp - n * (dot(tmp, n) / dot(n, n)));
    let d: vec3<f32> = (select(tmp_1, (1.0f * (tmp_1 / sqrt(dot(tmp_1, tmp_1)))), dot(tmp_1, tmp_1) > 1.0f * 1.0f) + (tangent * (dot(vec3<f32>(1.0, 0.0, 0.0), tangent) / dot(tangent, tangent))));
    let tmp_2 = rt_inverse3(mat3x3<f32>(n, tangent, cross(n, tangent)));
    let p: vec3<f32> = ((to_object * vec4<f32>(d, 1.0)).xyz + vec3<f32>(tmp_2[0][0u], tmp_2[1][0u], tmp_2[2][0u]));
    let phase: f32 = (rt_rem_euclid((p.x * 3.0f), 1.0f) + (log2((abs(p.y) + 1.0f)) * 0.30102999566f));
    let tmp_3 = i;
    rt_bufstore_vec4f(out_1, tmp_3, vec4<f32>(p, (phase + f32(((i << (7u & 31u)) | (i >> ((32u - (7u & 31u)) & 31u)))))));
}
