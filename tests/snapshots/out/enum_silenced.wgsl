// any_hit program `enum_silenced`

struct KindShade {
    color: vec3<f32>,
    hit: u32,
}

struct SurfaceHit {
    normal: vec3<f32>,
    material: u32,
}

fn rtp_enum_silenced(prd: ptr<function, KindShade>, attr: SurfaceHit) {
    (*prd).hit = 2u;
}
