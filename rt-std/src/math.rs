//! Shading math with GLSL/WGSL semantics, beside glam's own methods.
//!
//! [`smoothstep`], [`step`], [`saturate`] and [`mix`] work on `f32`, `Vec2`,
//! `Vec3` and `Vec4` ([`GenType`]), component by component, as their WGSL
//! builtins do.

use glam::{Vec2, Vec3, Vec4};

/// The reflection of incident direction `i` about the plane with normal `n`:
/// `i - 2 * dot(n, i) * n`. `n` should be normalised.
///
/// Program kinds: all.
pub fn reflect(i: Vec3, n: Vec3) -> Vec3 {
    i - 2.0 * n.dot(i) * n
}

/// The refraction of incident direction `i` through the surface with normal
/// `n` and ratio of indices of refraction `eta` (outside over inside when
/// `i` enters), as GLSL: with `k = 1 - eta^2 * (1 - dot(n, i)^2)`, the zero
/// vector if `k < 0` (total internal reflection), else
/// `eta * i - (eta * dot(n, i) + sqrt(k)) * n`. `i` and `n` should be
/// normalised, and `n` face against `i`.
///
/// Program kinds: all.
pub fn refract(i: Vec3, n: Vec3, eta: f32) -> Vec3 {
    let d = n.dot(i);
    let k = 1.0 - eta * eta * (1.0 - d * d);
    if k < 0.0 { Vec3::ZERO } else { eta * i - (eta * d + k.sqrt()) * n }
}

/// `n` turned to face against `i`: `n` if `dot(nref, i) < 0`, else `-n`.
///
/// This is GLSL's and WGSL's `faceForward`. OptiX's CUDA helper of the same
/// name has the opposite sign convention (its samples pass `-ray.direction`);
/// here pass the incident direction itself:
/// `faceforward(n, ray.direction, geometric_normal)`.
///
/// Program kinds: all.
pub fn faceforward(n: Vec3, i: Vec3, nref: Vec3) -> Vec3 {
    if nref.dot(i) < 0.0 { n } else { -n }
}

/// Hermite interpolation from 0 at `e0` to 1 at `e1`, per component: with
/// `t = saturate((x - e0) / (e1 - e0))`, `t * t * (3 - 2 * t)`. Undefined
/// (NaN or infinite) when `e0 == e1`, as in WGSL.
///
/// Program kinds: all.
pub fn smoothstep<T: GenType>(e0: T, e1: T, x: T) -> T {
    T::zip3(e0, e1, x, |e0, e1, x| {
        let t = saturate((x - e0) / (e1 - e0));
        t * t * (3.0 - 2.0 * t)
    })
}

/// Per component: 1 if `x >= edge`, else 0.
///
/// Program kinds: all.
pub fn step<T: GenType>(edge: T, x: T) -> T {
    T::zip3(edge, x, x, |edge, x, _| if x >= edge { 1.0 } else { 0.0 })
}

/// Per component: `x` clamped to `[0, 1]` (NaN becomes 0, as GPUs'
/// saturate does). The sign of a zero is kept (`-0.0` stays `-0.0`), as the
/// WGSL `saturate` the GPU backend runs gives it, in every build: written
/// with comparisons, not `f32::max`/`min`, whose sign of zero is left to the
/// optimiser (debug and release builds differed).
///
/// Program kinds: all.
pub fn saturate<T: GenType>(x: T) -> T {
    T::zip3(x, x, x, |x, _, _| {
        if x.is_nan() || x < 0.0 {
            0.0
        } else if x > 1.0 {
            1.0
        } else {
            x
        }
    })
}

/// Linear blend from `a` (at `t = 0`) to `b` (at `t = 1`):
/// `a * (1 - t) + b * t`, per component, with `t` either one `f32` for all
/// components or a value of `a`'s type.
///
/// Program kinds: all.
#[doc(alias = "lerp")]
pub fn mix<T: GenType, U: MixFactor<T>>(a: T, b: T, t: U) -> T {
    U::mix(a, b, t)
}

mod sealed {
    pub trait Sealed {}
}

/// The types the generic math helpers accept: `f32`, `Vec2`, `Vec3`,
/// `Vec4` (GLSL's *genType*, WGSL's float scalar or vector). Sealed.
pub trait GenType: sealed::Sealed + Copy {
    /// Applies `f` to corresponding components.
    #[doc(hidden)]
    fn zip3(a: Self, b: Self, c: Self, f: impl Fn(f32, f32, f32) -> f32) -> Self;
}

/// What [`mix`] accepts as its blend factor for values of type `T`: `f32`,
/// or `T` itself for a factor per component. Sealed.
pub trait MixFactor<T: GenType>: sealed::Sealed + Copy {
    /// `a * (1 - t) + b * t`.
    #[doc(hidden)]
    fn mix(a: T, b: T, t: Self) -> T;
}

impl sealed::Sealed for f32 {}

impl GenType for f32 {
    fn zip3(a: f32, b: f32, c: f32, f: impl Fn(f32, f32, f32) -> f32) -> f32 {
        f(a, b, c)
    }
}

impl MixFactor<f32> for f32 {
    fn mix(a: f32, b: f32, t: f32) -> f32 {
        a * (1.0 - t) + b * t
    }
}

macro_rules! gen_vector {
    ($v:ty, $($c:ident),+) => {
        impl sealed::Sealed for $v {}

        impl GenType for $v {
            fn zip3(a: $v, b: $v, c: $v, f: impl Fn(f32, f32, f32) -> f32) -> $v {
                <$v>::new($(f(a.$c, b.$c, c.$c)),+)
            }
        }

        impl MixFactor<$v> for $v {
            fn mix(a: $v, b: $v, t: $v) -> $v {
                a * (1.0 - t) + b * t
            }
        }

        impl MixFactor<$v> for f32 {
            fn mix(a: $v, b: $v, t: f32) -> $v {
                a * (1.0 - t) + b * t
            }
        }
    };
}

gen_vector!(Vec2, x, y);
gen_vector!(Vec3, x, y, z);
gen_vector!(Vec4, x, y, z, w);

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).abs().max_element() < 1e-6
    }

    #[test]
    fn reflect_mirrors_about_the_normal() {
        let i = Vec3::new(1.0, -1.0, 0.0);
        assert_eq!(reflect(i, Vec3::Y), Vec3::new(1.0, 1.0, 0.0));
        // Reflection keeps length and flips the normal component.
        let n = Vec3::new(0.0, 0.6, 0.8);
        let r = reflect(Vec3::new(0.3, -0.4, 0.5), n);
        assert!(close(r, Vec3::new(0.3, -0.4, 0.5) - 2.0 * 0.16 * n));
    }

    #[test]
    fn refract_follows_snell_and_total_internal_reflection() {
        // Straight through at normal incidence, any eta.
        assert!(close(refract(-Vec3::Y, Vec3::Y, 1.0 / 1.5), -Vec3::Y));
        // Snell: sin(t) = eta * sin(i), for i at 45 degrees into glass.
        let i = Vec3::new(1.0, -1.0, 0.0).normalize();
        let eta = 1.0 / 1.5;
        let t = refract(i, Vec3::Y, eta);
        assert!((t.length() - 1.0).abs() < 1e-6);
        assert!((t.x - eta * i.x).abs() < 1e-6);
        let cos_t = (1.0 - eta * eta * 0.5f32).sqrt();
        assert!(close(t, Vec3::new(eta * i.x, -cos_t, 0.0)));
        // From glass to air at 45 degrees: beyond the critical angle.
        assert_eq!(refract(i, Vec3::Y, 1.5), Vec3::ZERO);
    }

    #[test]
    fn faceforward_turns_against_the_incident_direction() {
        assert_eq!(faceforward(Vec3::Y, -Vec3::Y, Vec3::Y), Vec3::Y);
        assert_eq!(faceforward(Vec3::Y, Vec3::Y, Vec3::Y), -Vec3::Y);
        // dot == 0 counts as "not against": -n.
        assert_eq!(faceforward(Vec3::Y, Vec3::X, Vec3::Y), -Vec3::Y);
        // The test uses nref, not n.
        assert_eq!(faceforward(Vec3::Z, -Vec3::Y, Vec3::Y), Vec3::Z);
    }

    #[test]
    fn smoothstep_step_saturate() {
        assert_eq!(smoothstep(0.0, 1.0, 0.5), 0.5);
        assert_eq!(smoothstep(0.0, 1.0, 0.25), 0.15625);
        assert_eq!(smoothstep(0.0, 1.0, -3.0), 0.0);
        assert_eq!(smoothstep(0.0, 1.0, 3.0), 1.0);
        assert_eq!(smoothstep(2.0, 4.0, 3.0), 0.5);
        assert_eq!(smoothstep(Vec3::ZERO, Vec3::new(1.0, 2.0, 4.0), Vec3::splat(1.0)), Vec3::new(1.0, 0.5, 0.15625));
        assert_eq!(step(0.5, 0.5), 1.0);
        assert_eq!(step(0.5, 0.49), 0.0);
        assert_eq!(step(Vec2::new(1.0, 2.0), Vec2::splat(1.5)), Vec2::new(1.0, 0.0));
        assert_eq!(saturate(-0.5), 0.0);
        assert_eq!(saturate(f32::NAN), 0.0);
        // The sign of zero: WGSL's answer, in debug and release builds.
        assert_eq!(saturate(-0.0f32).to_bits(), (-0.0f32).to_bits());
        assert_eq!(saturate(f32::NAN).to_bits(), 0.0f32.to_bits());
        assert_eq!(saturate(-0.5f32).to_bits(), 0.0f32.to_bits());
        assert_eq!(saturate(Vec4::new(-1.0, 0.25, 1.0, 7.0)), Vec4::new(0.0, 0.25, 1.0, 1.0));
        assert_eq!(saturate(Vec3::new(f32::NAN, 2.0, 0.5)), Vec3::new(0.0, 1.0, 0.5));
    }

    #[test]
    fn mix_blends_with_scalar_or_per_component_factors() {
        assert_eq!(mix(2.0, 4.0, 0.25), 2.5);
        assert_eq!(mix(Vec3::ZERO, Vec3::new(2.0, 4.0, 8.0), 0.5), Vec3::new(1.0, 2.0, 4.0));
        assert_eq!(mix(Vec2::ZERO, Vec2::splat(4.0), Vec2::new(0.25, 1.0)), Vec2::new(1.0, 4.0));
        // Exactly a * (1 - t) + b * t: the end points are exact, even with
        // values whose difference overflows.
        assert_eq!(mix(-f32::MAX, f32::MAX, 1.0), f32::MAX);
        assert_eq!(mix(Vec4::splat(3.0), Vec4::splat(7.0), 0.0), Vec4::splat(3.0));
        let (a, b, t) = (0.1f32, 0.7f32, 0.3f32);
        assert_eq!(mix(a, b, t).to_bits(), (a * (1.0 - t) + b * t).to_bits());
    }
}
