// closest_hit program `methods_shade`

struct BallHit {
    normal: vec3<f32>,
    t: f32,
}

struct Glow {
    color: vec3<f32>,
    bounces: u32,
}

const Glow__MAX_BOUNCES: u32 = 4u;

fn rtm_BallHit__facing(self_: BallHit, dir: vec3<f32>) -> vec3<f32> {
    var tmp: vec3<f32>;
    if (dot(self_.normal, dir) < 0.0f) {
        tmp = self_.normal;
    } else {
        tmp = -self_.normal;
    }
    return tmp;
}

fn rtm_Glow__add(self_: ptr<function, Glow>, c: vec3<f32>) {
    if ((*self_).bounces < Glow__MAX_BOUNCES) {
        (*self_).color += c;
        (*self_).bounces += 1u;
    }
}

fn rtm_Glow__luminance(self_: Glow) -> f32 {
    return dot(self_.color, vec3<f32>(0.2126f, 0.7152f, 0.0722f));
}

fn rtp_methods_shade(prd: ptr<function, Glow>, attr: BallHit) {
    let n: vec3<f32> = rtm_BallHit__facing(attr, rt_current_ray().direction);
    rtm_Glow__add(prd, ((n * 0.5f) + 0.5f));
    let l: f32 = rtm_Glow__luminance((*prd));
    rtm_Glow__add(prd, vec3<f32>((l * attr.t)));
}
