//! [`Ray`] and the ray flags of [`rt_trace_with`](crate::rt_trace_with).

use glam::Vec3;

use crate::data::RtData;
use crate::layout::{FieldLayout, LayoutKind, ScalarKind, TypeLayout};

const VEC3: LayoutKind = LayoutKind::Vector { scalar: ScalarKind::F32, len: 3 };

/// A ray: origin, direction, ray type and the parametric interval
/// `(tmin, tmax)` in which intersections count.
///
/// The direction need not be normalised; distances are in units of its
/// length. In WGSL it is the struct `RtRay`, nine packed words.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: Vec3,
    /// Where it goes.
    pub direction: Vec3,
    /// Which ray type it is: selects the miss program and each material's
    /// closest-hit and any-hit programs.
    pub ray_type: u32,
    /// Intersections at `t <= tmin` are ignored (usually a scene epsilon).
    pub tmin: f32,
    /// Intersections at `t >= tmax` are ignored; shrinks as hits are
    /// committed. `f32::INFINITY` is allowed.
    pub tmax: f32,
}

impl Ray {
    /// A ray from its parts.
    ///
    /// Program kinds: all.
    #[doc(alias = "make_Ray")]
    pub const fn new(origin: Vec3, direction: Vec3, ray_type: u32, tmin: f32, tmax: f32) -> Ray {
        Ray { origin, direction, ray_type, tmin, tmax }
    }

    /// Whether [`rt_trace`](crate::rt_trace) accepts the ray: origin and
    /// direction finite, `tmin` and `tmax` not NaN (`tmax` may be infinite).
    /// Tracing a ray that fails this raises
    /// [`EXCEPTION_INVALID_RAY`](crate::EXCEPTION_INVALID_RAY) instead.
    ///
    /// Program kinds: all.
    pub fn is_valid(&self) -> bool {
        self.origin.is_finite() && self.direction.is_finite() && !self.tmin.is_nan() && !self.tmax.is_nan()
    }
}

impl RtData for Ray {
    const LAYOUT: TypeLayout = TypeLayout {
        kind: crate::layout::LayoutKind::Builtin,
        rust: "Ray",
        wgsl: "RtRay",
        words: 9,
        fields: &[
            FieldLayout { name: "origin", ty: "Vec3", kind: VEC3, offset_words: 0 },
            FieldLayout { name: "direction", ty: "Vec3", kind: VEC3, offset_words: 3 },
            FieldLayout { name: "ray_type", ty: "u32", kind: LayoutKind::Scalar(ScalarKind::U32), offset_words: 6 },
            FieldLayout { name: "tmin", ty: "f32", kind: LayoutKind::Scalar(ScalarKind::F32), offset_words: 7 },
            FieldLayout { name: "tmax", ty: "f32", kind: LayoutKind::Scalar(ScalarKind::F32), offset_words: 8 },
        ],
    };

    fn write_words(&self, out: &mut [u32]) {
        self.origin.write_words(&mut out[0..3]);
        self.direction.write_words(&mut out[3..6]);
        self.ray_type.write_words(&mut out[6..7]);
        self.tmin.write_words(&mut out[7..8]);
        self.tmax.write_words(&mut out[8..9]);
    }

    fn read_words(words: &[u32]) -> Self {
        Ray {
            origin: Vec3::read_words(&words[0..3]),
            direction: Vec3::read_words(&words[3..6]),
            ray_type: u32::read_words(&words[6..7]),
            tmin: f32::read_words(&words[7..8]),
            tmax: f32::read_words(&words[8..9]),
        }
    }
}

/// No flags: the default of [`rt_trace`](crate::rt_trace).
pub const RAY_FLAG_NONE: u32 = rt_abi::RAY_FLAG_NONE;
/// End the search at the first accepted intersection (a shadow ray).
pub const RAY_FLAG_TERMINATE_ON_FIRST_HIT: u32 = rt_abi::RAY_FLAG_TERMINATE_ON_FIRST_HIT;
/// Skip any-hit programs: every reported intersection is accepted.
pub const RAY_FLAG_DISABLE_ANYHIT: u32 = rt_abi::RAY_FLAG_DISABLE_ANYHIT;
/// Skip the closest-hit program of the committed intersection.
pub const RAY_FLAG_DISABLE_CLOSESTHIT: u32 = rt_abi::RAY_FLAG_DISABLE_CLOSESTHIT;
/// Ignore triangles whose back faces the ray.
pub const RAY_FLAG_CULL_BACK_FACING: u32 = rt_abi::RAY_FLAG_CULL_BACK_FACING;
/// Ignore triangles whose front faces the ray.
pub const RAY_FLAG_CULL_FRONT_FACING: u32 = rt_abi::RAY_FLAG_CULL_FRONT_FACING;

/// The visibility mask [`rt_trace`](crate::rt_trace) uses: every bit of an
/// instance's 8-bit mask, as OptiX's `RT_VISIBILITY_ALL`.
#[doc(alias = "RT_VISIBILITY_ALL")]
pub const RAY_MASK_ALL: u32 = rt_abi::RAY_MASK_ALL;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_round_trips_through_words() {
        let ray = Ray::new(Vec3::new(1.0, -2.0, 3.5), Vec3::new(0.0, 0.6, -0.8), 7, 1e-3, f32::INFINITY);
        let mut words = [0u32; 9];
        ray.write_words(&mut words);
        assert_eq!(words[6], 7);
        assert_eq!(words[7], 1e-3f32.to_bits());
        assert_eq!(Ray::read_words(&words), ray);
        assert_eq!(Ray::LAYOUT.words as usize, words.len());
    }

    #[test]
    fn ray_layout_fields_are_packed() {
        let fields = Ray::LAYOUT.fields;
        let sizes = [3, 3, 1, 1, 1];
        let mut offset = 0;
        for (field, size) in fields.iter().zip(sizes) {
            assert_eq!(field.offset_words, offset, "{}", field.name);
            offset += size;
        }
        assert_eq!(offset, Ray::LAYOUT.words);
    }

    #[test]
    fn validity() {
        let ok = Ray::new(Vec3::ZERO, Vec3::Z, 0, 0.0, f32::INFINITY);
        assert!(ok.is_valid());
        assert!(!Ray { origin: Vec3::new(f32::NAN, 0.0, 0.0), ..ok }.is_valid());
        assert!(!Ray { direction: Vec3::new(0.0, f32::INFINITY, 0.0), ..ok }.is_valid());
        assert!(!Ray { tmax: f32::NAN, ..ok }.is_valid());
    }
}
