// miss program `shine_miss`

struct Lamp {
    power: f32,
}

struct ShineRay {
    energy: f32,
}

const Lamp__SCALE: f32 = 1.0f;

const ShineRay__SCALE: f32 = 0.5f;

fn rtf_brighter__Lamp(s: Lamp, h: f32) -> f32 {
    return (rtm_Lamp__shine(s, h) + Lamp__SCALE);
}

fn rtf_brighter__ShineRay(s: ShineRay, h: f32) -> f32 {
    return (rtm_ShineRay__shine(s, h) + ShineRay__SCALE);
}

fn rtm_Lamp__level(self_: Lamp) -> f32 {
    return self_.power;
}

fn rtm_Lamp__shine(self_: Lamp, by: f32) -> f32 {
    return ((rtm_Lamp__level(self_) * by) * Lamp__SCALE);
}

fn rtm_ShineRay__level(self_: ShineRay) -> f32 {
    return self_.energy;
}

fn rtm_ShineRay__shine(self_: ShineRay, by: f32) -> f32 {
    return (self_.energy + (by * ShineRay__SCALE));
}

fn rtp_shine_miss(prd: ptr<function, ShineRay>) {
    let lamp: Lamp = Lamp(2.0f);
    (*prd).energy = (((rtm_Lamp__shine(lamp, (*prd).energy) + rtf_brighter__Lamp(lamp, 1.0f)) + rtf_brighter__ShineRay((*prd), 0.5f)) + rtm_ShineRay__shine((*prd), 1.0f));
}
