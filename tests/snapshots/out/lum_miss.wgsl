// miss program `lum_miss`

struct GlowRay {
    l: Lum,
}

struct Lum {
    c: vec3<f32>,
}

fn rto_Lum__add__Lum(self_: Lum, o: Lum) -> Lum {
    return Lum((self_.c + o.c));
}

fn rto_Lum__add_assign__Lum(self_: ptr<function, Lum>, o: Lum) {
    (*self_).c += o.c;
}

fn rto_Lum__index__usize(self_: Lum, i: u32) -> f32 {
    return self_.c[i];
}

fn rto_Lum__mul__Lum(self_: Lum, o: Lum) -> Lum {
    return Lum((self_.c * o.c));
}

fn rto_Lum__mul__f32(self_: Lum, k: f32) -> Lum {
    return Lum((self_.c * k));
}

fn rto_Lum__neg(self_: Lum) -> Lum {
    return Lum(-self_.c);
}

fn rtp_lum_miss(prd: ptr<function, GlowRay>) {
    let sky: Lum = Lum(vec3<f32>(0.5f, 0.7f, 1.0f));
    var l: Lum = rto_Lum__add__Lum(rto_Lum__mul__Lum((*prd).l, sky), rto_Lum__mul__f32(sky, 0.5f));
    rto_Lum__add_assign__Lum(&l, rto_Lum__neg((*prd).l));
    (*prd).l = l;
    (*prd).l.c.x = rto_Lum__index__usize(l, 1u);
}
