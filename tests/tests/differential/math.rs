//! Scalar math functions and shading helpers.

use super::*;

// ---------------------------------------------------------------------------
// Scalar math
// ---------------------------------------------------------------------------

/// Positive floats from tiny to huge.
fn positives() -> Vec<f32> {
    let mut v: Vec<f32> = f64_grid().into_iter().map(f32::abs).filter(|&x| x > 0.0).collect();
    v.extend(spread(64 - v.len(), 0.5, 2.0));
    v
}

differential! {
    /// `f32` methods: roots, powers, exponentials, logarithms, trigonometry,
    /// rounding, comparisons, tests and constants.
    fn scalar_math {
        /// `sqrt`: WGSL inherits it from `1 / inverseSqrt(x)`: 2 ULP, then a
        /// 2.5 ULP division.
        sqrt(x: f32) -> [f32; 2] over one(&positives()), tol ulp(5) => {
            [x.sqrt(), (x * 0.25).sqrt()]
        }
        /// `exp` and `exp2`: WGSL, 3 + 2 * |x| ULP (|x| <= 10 here).
        exp(x: f32) -> [f32; 2] over one(&spread(64, -10.0, 10.0)), tol ulp(23) => {
            [x.exp(), x.exp2()]
        }
        /// `ln` and `log2`: WGSL, 3 ULP outside [0.5, 2], absolute error
        /// 2^-21 inside.
        logarithms(x: f32) -> [f32; 2] over one(&positives()), tol ulp_or_abs(3, 2.0f32.powi(-21)) => {
            [x.ln(), x.log2()]
        }
        /// `sin` and `cos` inside `[-pi, pi]`: WGSL, absolute error 2^-11.
        sin_cos(x: f32) -> [f32; 2] over one(&spread(64, -3.14159, 3.14159)), tol ulp_or_abs(0, 2.0f32.powi(-11)) => {
            [x.sin(), x.cos()]
        }
        /// `tan`: WGSL inherits it from `sin(x) / cos(x)`; with |x| <= 1.2,
        /// |cos| >= 0.36 and the 2^-11 errors of both give less than 5e-3.
        tan(x: f32) -> [f32; 1] over one(&spread(64, -1.2, 1.2)), tol ulp_or_abs(0, 5e-3) => {
            [x.tan()]
        }
        /// `atan`: WGSL, 4096 ULP.
        atan(x: f32) -> [f32; 1] over one(&f64_grid()), tol ulp(4096) => {
            [x.atan()]
        }
        /// `atan2`: WGSL, 4096 ULP for |x| in [2^-126, 2^126] and `y` finite
        /// and normal: not for zeros (`atan2(0, 0)` is 0 in Rust, 3pi/4 on
        /// lavapipe).
        atan2(y: f32, x: f32) -> [f32; 1] over pairs_where(&F16, &F16, |y, x| y != 0.0 && x != 0.0), tol ulp(4096) => {
            [y.atan2(x)]
        }
        /// `asin` and `acos`: WGSL, the worse of an absolute 6.8e-5 and
        /// inheritance from `atan2(x, sqrt(1 - x * x))` (4096 ULP, plus the
        /// error of `1 - x * x` where |x| is near 1).
        asin_acos(x: f32) -> [f32; 2] over one(&spread(64, -1.0, 1.0)), tol ulp_or_abs(4096, 2e-4) => {
            [x.asin(), x.acos()]
        }
        /// Hyperbolic functions: WGSL inherits them from their `exp`
        /// formulas (`(exp(x) - exp(-x)) / 2`, ...): 3 + 2 * |x| ULP of each
        /// `exp` (|x| <= 4), absolute where the difference cancels.
        hyperbolic(x: f32) -> [f32; 3] over one(&spread(64, -4.0, 4.0)), tol ulp_or_abs(16, 2e-5) => {
            [x.sinh(), x.cosh(), x.tanh()]
        }
        /// Inverse hyperbolic functions: WGSL inherits them from their `log`
        /// formulas (`log(x + sqrt(x * x + 1))`, ...): `log`'s 2^-21
        /// absolute error near 1.
        inverse_hyperbolic(x: f32) -> [f32; 3] over one(&spread(64, -0.95, 0.95)), tol ulp_or_abs(16, 2e-6) => {
            [x.asinh(), (x.abs() + 1.0 + x * x).acosh(), x.atanh()]
        }
        /// `powi` is repeated squaring on both sides (compiler-rt's
        /// `__powisf2`, the compiler's `rt_powi`): exact for n >= 0; negative
        /// powers divide (2.5 ULP).
        powi(x: f32, n: i32) -> [f32; 1]
            over pairs(&spread(16, -8.0, 8.0), &[-6, -3, -1, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12]), tol ulp(3) => {
            [x.powi(n)]
        }
        /// `powf` with positive bases: WGSL inherits `pow` from
        /// `exp2(y * log2(x))`: 3 + 2 * |y log2 x| ULP (<= 23 here) plus
        /// `log2`'s error times |y|: under 64 ULP.
        powf(x: f32, y: f32) -> [f32; 1] over pairs(&spread(16, 0.1, 10.0), &spread(16, -3.0, 3.0)), tol ulp(64) => {
            [x.powf(y)]
        }
        /// `mul_add` is fused in Rust; WGSL's `fma` is inherited from
        /// `a * b + c` (may round the product): absolute, |a * b| <= 1e4.
        mul_add(a: f32, b: f32) -> [f32; 2]
            over pairs(&spread(16, -100.0, 100.0), &spread(16, -7.0, 7.0)), tol ulp_or_abs(1, 5e-4) => {
            [a.mul_add(b, 0.3), b.mul_add(a, -a * b)]
        }
        /// `recip` is a division (2.5 ULP); `to_radians` and `to_degrees`
        /// multiply by a constant (WGSL: inherited, 1 ULP with the constant's
        /// rounding).
        recip_degrees(x: f32) -> [f32; 3] over one(&f64_grid()[2..]), tol ulp(3) => {
            [x.recip(), x.to_radians(), x.to_degrees()]
        }
        /// Rounding (exact): `floor`, `ceil`, `trunc`, Rust's `round` (half
        /// away from zero), `round_ties_even`, `fract` (`x - trunc(x)`).
        rounding(x: f32) -> [f32; 6] over one(&f64_grid()) => {
            [x.floor(), x.ceil(), x.trunc(), x.round(), x.round_ties_even(), x.fract()]
        }
        /// `abs`, `signum` (1 for +0.0; not given -0.0), `min`, `max`,
        /// `clamp`, `f32::max`-style calls (exact).
        sign_min_max(x: f32, y: f32) -> [f32; 7] over pairs(&F16.map(|x| x + 0.0), &F16) => {
            [x.abs(), x.signum(), x.min(y), x.max(y), x.clamp(-1.0, 2.0), f32::max(x, 0.0), f32::min(y, PI)]
        }
        /// `hypot` (Rust: libm's, ~1 ULP; WGSL: `length(vec2(x, y))`,
        /// inherited from `sqrt(x * x + y * y)`).
        hypot(x: f32, y: f32) -> [f32; 1] over pairs(&F16[..13], &F16[..13]), tol ulp(8) => {
            [x.hypot(y)]
        }
        /// `is_nan`, `is_finite`, `is_infinite` on finite values (WGSL may
        /// assume there are no others), and the float constants.
        tests_and_constants(x: f32) -> [f32; 4] over one(&f64_grid()), tol CHAINED => {
            let nan = x.is_nan() as u32 + 8 * (x * 0.0).is_nan() as u32;
            let flags = nan + 2 * x.is_finite() as u32 + 4 * x.is_infinite() as u32;
            let consts = TAU * FRAC_1_PI + E * LN_2 + SQRT_2 * FRAC_PI_4 + FRAC_PI_2 + core::f32::consts::FRAC_PI_3;
            let limits = f32::MAX.min(x) + f32::MIN_POSITIVE + f32::EPSILON - f32::MIN.abs().min(1.0);
            [flags as f32, consts, limits, if x < f32::INFINITY && x > f32::NEG_INFINITY { 1.0 } else { 0.0 }]
        }
    }
}

// ---------------------------------------------------------------------------
// Shading helpers
// ---------------------------------------------------------------------------

differential! {
    /// rt-std's GLSL-style helpers: `reflect`, `refract`, `faceforward`,
    /// `smoothstep`, `mix`, `step`, `saturate`.
    fn shading_helpers {
        /// `reflect` (WGSL: inherited from `i - 2 * dot(n, i) * n`).
        reflect_fn(i: Vec3, n: Vec3) -> [Vec3; 1]
            over pairs(&units(16, 40), &units(16, 41)), tol ulp_or_abs(4, 1e-6) => {
            [reflect(i, n)]
        }
        /// `refract`, total internal reflection (zero vector) included
        /// (WGSL: inherited from its formula).
        refract_fn(i: Vec3, n: Vec3, eta: f32) -> [Vec3; 1]
            over triples(&units(8, 42), &units(8, 43), &[1.0 / 1.5, 1.0, 1.5, 2.4]), tol ulp_or_abs(8, 2e-6) => {
            let n = if n.dot(i) > 0.0 { -n } else { n };
            [refract(i, n, eta)]
        }
        /// `faceforward`: `n` if `dot(nref, i) < 0`, else `-n` (exact).
        faceforward_fn(i: Vec3, n: Vec3) -> [Vec3; 2] over pairs(&units(16, 44), &units(16, 45)) => {
            [faceforward(n, i, n), faceforward(n * 2.0, -i, Vec3::Y)]
        }
        /// `smoothstep` on scalars and vectors (WGSL: inherited from
        /// `t * t * (3 - 2 * t)` with `t = clamp((x - e0) / (e1 - e0))`).
        smoothstep_fn(x: f32, e: f32) -> [f32; 3]
            over pairs(&spread(16, -1.0, 2.0), &[0.0, 0.25, -1.0, 0.9, 1.0, 0.3, -0.5, 0.1]),
            tol ulp_or_abs(8, 1e-6) => {
            let v = smoothstep(vec3(e, 0.0, -2.0), vec3(e + 1.0, 2.0, 5.0), Vec3::splat(x));
            [smoothstep(e, e + 0.5, x), v.x + v.y, v.z]
        }
        /// `mix` with a scalar and a per-component factor (WGSL: inherited
        /// from `a * (1 - t) + b * t`, the same formula, possibly fused).
        mix_fn(a: Vec3, b: Vec3, t: f32) -> [Vec3; 3]
            over triples(&vec3s(8, 10.0, 46), &vec3s(8, 10.0, 47), &[0.0, 1.0, 0.5, 0.3]), tol ulp_or_abs(2, 2e-6) => {
            [mix(a, b, t), mix(a, b, vec3(t, 1.0 - t, 0.25)), Vec3::splat(mix(a.x, b.y, t))]
        }
        /// `step` and `saturate` on scalars and vectors (exact).
        step_saturate(x: f32, e: f32) -> [f32; 6] over pairs(&F16, &[0.0, 0.5, -0.5, 1.0, 2.5, 1e-3, -0.0, 7.0]) => {
            let v = step(vec2(e, -e), Vec2::splat(x));
            let s = saturate(vec4(x, -x, x * 0.5, e));
            [step(e, x), v.x - v.y, saturate(x), saturate(x - e), s.x + s.y, s.z * s.w]
        }
    }
}
