// miss program `consts`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

const BIAS: i32 = -2i;

const CELLS: u32 = (STRATA * STRATA);

const HORIZON: vec3<f32> = vec3<f32>(0.9f, 0.9f, 1.0f);

const RADIANCE_RAY: u32 = 0u;

const STOPS: array<f32, 3> = array<f32, 3>(0.5f, 1.0f, 2.0f);

const STRATA: u32 = 4u;

const ZENITH: vec3<f32> = vec3<f32>(0.2f, 0.4f, 0.9f);

fn rtp_consts(prd: ptr<function, Radiance>) {
    const GAMMA: f32 = (1.0f / 2.2f);
    const STEPS: i32 = 3i;
    let FAR: f32 = rt_f32_from_bits(0x7f800000u);
    let d: vec3<f32> = rt_current_ray().direction;
    let t: f32 = max(d.y, 0.0f);
    let tmp = pow(t, GAMMA);
    let sky: vec3<f32> = (HORIZON * (1.0 - tmp) + ZENITH * tmp);
    let cell: u32 = (u32((((*prd).depth + BIAS) + STEPS)) % CELLS);
    var stops: array<f32, 3> = STOPS;
    let exposure: f32 = (stops[((cell % STRATA) % 3u)] + STOPS[(cell % 3u)]);
    (*prd).result = ((sky * exposure) * f32(RADIANCE_RAY));
    (*prd).importance = min((*prd).importance, FAR);
}
