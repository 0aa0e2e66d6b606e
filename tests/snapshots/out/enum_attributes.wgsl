// closest_hit program `enum_attributes`

struct KindShade {
    color: vec3<f32>,
    hit: u32,
}

struct SurfaceHit {
    normal: vec3<f32>,
    material: u32,
}

fn rtp_enum_attributes(prd: ptr<function, KindShade>, attr: SurfaceHit) {
    (*prd).hit = attr.material;
    var tmp: vec3<f32>;
    switch attr.material {
        case 0u: {
            tmp = attr.normal;
        }
        default: {
            tmp = vec3<f32>(1.0);
        }
    }
    (*prd).color = tmp;
}
