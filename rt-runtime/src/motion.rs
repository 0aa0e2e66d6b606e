//! Motion transforms (OptiX 6's `rtTransformSetMotionKeys`,
//! `rtTransformSetMotionRange`, `rtTransformSetMotionBorderMode` with
//! `RT_MOTIONBORDERMODE_CLAMP`): two or more keys spread evenly over a time
//! range, the transform at a ray's time interpolated between the two keys
//! around it, and a box that holds the child at every time.
//!
//! The arithmetic here is the reference: the CPU backend calls it, and the
//! compute traversal's `rt_motion_matrix` (`backend/wgpu/compute/graph.wgsl`)
//! does the same steps on the keys `MotionTransform::encode` writes.

use glam::{Mat4, Quat, Vec3, Vec4};
use obvhs::aabb::Aabb as OAabb;

/// One scale-rotate-translate key (OptiX's `RT_MOTIONKEYTYPE_SRT`, without
/// its shear and pivot): the matrix `T * R * S`, a point scaled, then
/// rotated about the origin, then translated. Between keys the scale and
/// translation are interpolated linearly and the rotation spherically
/// (slerp on the shorter arc).
#[doc(alias = "RT_MOTIONKEYTYPE_SRT")]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Srt {
    /// Scale along x, y and z.
    pub scale: Vec3,
    /// A unit quaternion (normalised on creation).
    pub rotation: Quat,
    /// Where the origin goes.
    pub translation: Vec3,
}

impl Srt {
    /// The key's matrix.
    pub fn matrix(&self) -> Mat4 {
        Mat4::from_scale_rotation_translation(self.scale, self.rotation, self.translation)
    }
}

/// A motion transform's keys.
#[derive(Clone, Debug, PartialEq)]
pub enum MotionKeys {
    /// Matrices (OptiX's `RT_MOTIONKEYTYPE_MATRIX_FLOAT12`), interpolated
    /// element by element.
    #[doc(alias = "RT_MOTIONKEYTYPE_MATRIX_FLOAT12")]
    Matrices(Vec<Mat4>),
    /// Scale-rotate-translate keys.
    Srt(Vec<Srt>),
}

impl MotionKeys {
    fn len(&self) -> usize {
        match self {
            MotionKeys::Matrices(m) => m.len(),
            MotionKeys::Srt(k) => k.len(),
        }
    }
}

/// A transform's motion: its keys over `[t0, t1]`, clamped outside it.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionTransform {
    /// The keys, spread evenly over `[t0, t1]`.
    pub keys: MotionKeys,
    /// The time of the first key.
    pub t0: f32,
    /// The time of the last key.
    pub t1: f32,
}

/// What [`MotionTransform::encode`] writes first: which kind of keys.
pub(crate) const KEYS_MATRICES: u32 = 0;
pub(crate) const KEYS_SRT: u32 = 1;

impl MotionTransform {
    /// Checks the keys and range: at least two keys, finite values, `t0 <=
    /// t1`, and rotations that are not zero (they are normalised).
    pub fn new(keys: MotionKeys, t0: f32, t1: f32) -> Result<MotionTransform, String> {
        if keys.len() < 2 {
            return Err(format!("a motion transform needs at least 2 keys, found {}", keys.len()));
        }
        check_range(t0, t1)?;
        let keys = match keys {
            MotionKeys::Matrices(m) => {
                if let Some(i) = m.iter().position(|k| !k.is_finite()) {
                    return Err(format!("motion key {i} is not finite: {:?}", m[i]));
                }
                // OptiX's keys are 3x4: affine by construction.
                if let Some(i) = m.iter().position(|k| k.row(3) != Vec4::W) {
                    return Err(format!("motion key {i} is not affine (its last row is {}, not 0 0 0 1)", m[i].row(3)));
                }
                MotionKeys::Matrices(m)
            }
            MotionKeys::Srt(k) => {
                let mut out = Vec::with_capacity(k.len());
                for (i, key) in k.iter().enumerate() {
                    let finite = key.scale.is_finite() && key.rotation.is_finite() && key.translation.is_finite();
                    let len = key.rotation.length();
                    if !finite || len == 0.0 || !len.is_finite() {
                        return Err(format!("motion key {i} is not finite or its rotation is zero: {key:?}"));
                    }
                    out.push(Srt { rotation: key.rotation / len, ..*key });
                }
                MotionKeys::Srt(out)
            }
        };
        Ok(MotionTransform { keys, t0, t1 })
    }

    /// The segment a time falls in and the fraction along it: the time
    /// clamped to the range, keys spread evenly over it (a range of one
    /// instant: the first key at or before it, the last after).
    pub(crate) fn segment(&self, time: f32) -> (usize, f32) {
        segment(self.keys.len(), self.t0, self.t1, time)
    }

    /// The object-to-world matrix at `time`.
    pub fn matrix_at(&self, time: f32) -> Mat4 {
        let (i, f) = self.segment(time);
        match &self.keys {
            MotionKeys::Matrices(m) => m[i] * (1.0 - f) + m[i + 1] * f,
            MotionKeys::Srt(k) => {
                let (a, b) = (k[i], k[i + 1]);
                let scale = a.scale * (1.0 - f) + b.scale * f;
                let translation = a.translation * (1.0 - f) + b.translation * f;
                Mat4::from_scale_rotation_translation(scale, slerp(a.rotation, b.rotation, f), translation)
            }
        }
    }

    /// A box that holds `child` (a box in the transform's child space) at
    /// every time, in the parent's space.
    ///
    /// Conservative because each segment's box holds every instant of it:
    /// for matrix keys, `M(t) x = (1 - f) M_i x + f M_i+1 x` lies between the
    /// two keys' images of `x`, so the union of the keys' boxes holds it; for
    /// SRT keys, the scaled point `S(t) x` lies in the union of the keys'
    /// scaled boxes (each component moves linearly), a rotation keeps its
    /// distance `r` from the origin, and the translation moves linearly
    /// between the keys', so the segment's translation box grown by `r`
    /// holds it, whatever path the slerp takes.
    pub(crate) fn bounds(&self, child: &OAabb) -> OAabb {
        if child.min.x > child.max.x {
            return *child;
        }
        let mut out = OAabb::empty();
        match &self.keys {
            MotionKeys::Matrices(m) => {
                for key in m {
                    out = out.union(&box_of(*key, child));
                }
            }
            MotionKeys::Srt(k) => {
                for pair in k.windows(2) {
                    let scaled = box_of(Mat4::from_scale(pair[0].scale), child)
                        .union(&box_of(Mat4::from_scale(pair[1].scale), child));
                    let r = Vec3::from(scaled.min.abs().max(scaled.max.abs())).length();
                    let lo = pair[0].translation.min(pair[1].translation) - Vec3::splat(r);
                    let hi = pair[0].translation.max(pair[1].translation) + Vec3::splat(r);
                    out = out.union(&OAabb::new(lo.into(), hi.into()));
                }
            }
        }
        out
    }

    /// The words the compute traversal reads (`rt_motion_matrix`):
    /// `[kind, key count, t0, t1]`, then per key 16 words (a matrix, column
    /// by column) or 12 (scale, 0, rotation xyzw, translation, 0).
    pub(crate) fn encode(&self, out: &mut Vec<u32>) {
        let kind = match self.keys {
            MotionKeys::Matrices(_) => KEYS_MATRICES,
            MotionKeys::Srt(_) => KEYS_SRT,
        };
        out.extend([kind, self.keys.len() as u32, self.t0.to_bits(), self.t1.to_bits()]);
        match &self.keys {
            MotionKeys::Matrices(m) => {
                for key in m {
                    out.extend(key.to_cols_array().map(f32::to_bits));
                }
            }
            MotionKeys::Srt(k) => {
                for key in k {
                    out.extend(key.scale.extend(0.0).to_array().map(f32::to_bits));
                    out.extend(Vec4::from(key.rotation).to_array().map(f32::to_bits));
                    out.extend(key.translation.extend(0.0).to_array().map(f32::to_bits));
                }
            }
        }
    }
}

/// Checks a motion range: finite, and `t0 <= t1`.
pub(crate) fn check_range(t0: f32, t1: f32) -> Result<(), String> {
    if !t0.is_finite() || !t1.is_finite() {
        return Err(format!("the motion range [{t0}, {t1}] is not finite"));
    }
    if t1 < t0 {
        return Err(format!("the motion range [{t0}, {t1}] ends before it begins"));
    }
    Ok(())
}

/// The segment of `n` keys (at least 2) spread evenly over `[t0, t1]` that
/// `time` falls in, and the fraction along it: the time clamped to the
/// range (a range of one instant: the first key at or before it, the last
/// after). The compute traversal's `rt_motion_segment` (prelude.wgsl) is
/// the same.
pub(crate) fn segment(n: usize, t0: f32, t1: f32, time: f32) -> (usize, f32) {
    let last = (n - 1) as f32;
    let u = if t1 > t0 {
        ((time - t0) / (t1 - t0)).clamp(0.0, 1.0) * last
    } else if time > t0 {
        last
    } else {
        0.0
    };
    // NaN times clamp to NaN: take the first key.
    let u = if u.is_nan() { 0.0 } else { u };
    let i = (u.floor() as usize).min(n - 2);
    (i, u - i as f32)
}

/// Spherical interpolation from `a` to `b` by `f`, on the shorter arc;
/// nearly equal rotations are interpolated linearly and normalised (the
/// arc's sine would divide by almost zero). The compute traversal's
/// `rt_slerp` is the same.
pub(crate) fn slerp(a: Quat, b: Quat, f: f32) -> Quat {
    let (a, mut b) = (Vec4::from(a), Vec4::from(b));
    let mut d = a.dot(b);
    if d < 0.0 {
        b = -b;
        d = -d;
    }
    let q = if d > 0.9995 {
        a + (b - a) * f
    } else {
        let theta = d.min(1.0).acos();
        (a * ((1.0 - f) * theta).sin() + b * (f * theta).sin()) / theta.sin()
    };
    Quat::from_vec4(q.normalize())
}

/// The box of `b`'s eight corners under `m`.
fn box_of(m: Mat4, b: &OAabb) -> OAabb {
    let mut out = OAabb::empty();
    for i in 0..8 {
        let p = Vec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        );
        out.extend(m.transform_point3(p).into());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shift(x: f32) -> Mat4 {
        Mat4::from_translation(Vec3::new(x, 0.0, 0.0))
    }

    #[test]
    fn keys_interpolate_and_clamp() {
        let m = MotionTransform::new(MotionKeys::Matrices(vec![shift(0.0), shift(2.0), shift(6.0)]), 1.0, 3.0).unwrap();
        assert_eq!(m.matrix_at(1.5).w_axis.x, 1.0);
        assert_eq!(m.matrix_at(2.5).w_axis.x, 4.0);
        assert_eq!(m.matrix_at(-7.0).w_axis.x, 0.0, "clamped before the range");
        assert_eq!(m.matrix_at(9.0).w_axis.x, 6.0, "clamped after it");
        assert_eq!(m.matrix_at(f32::NAN).w_axis.x, 0.0);
        let one = MotionTransform::new(MotionKeys::Matrices(vec![shift(0.0), shift(2.0)]), 1.0, 1.0).unwrap();
        assert_eq!((one.matrix_at(1.0).w_axis.x, one.matrix_at(1.5).w_axis.x), (0.0, 2.0));
    }

    #[test]
    fn srt_rotation_is_slerped() {
        let key =
            |angle: f32| Srt { scale: Vec3::ONE, rotation: Quat::from_rotation_z(angle), translation: Vec3::ZERO };
        let m = MotionTransform::new(MotionKeys::Srt(vec![key(0.0), key(160f32.to_radians())]), 0.0, 1.0).unwrap();
        // A quarter of the way: 40 degrees, length kept (a lerp of the
        // matrices would shrink it).
        let p = m.matrix_at(0.25).transform_point3(Vec3::X);
        let (s, c) = 40f32.to_radians().sin_cos();
        assert!((p - Vec3::new(c, s, 0.0)).length() < 1e-6, "{p}");
    }

    #[test]
    fn bad_keys_are_refused() {
        assert!(MotionTransform::new(MotionKeys::Matrices(vec![shift(0.0)]), 0.0, 1.0).unwrap_err().contains("2 keys"));
        let two = MotionKeys::Matrices(vec![shift(0.0), shift(1.0)]);
        assert!(MotionTransform::new(two.clone(), 1.0, 0.0).unwrap_err().contains("ends before"));
        assert!(MotionTransform::new(two, f32::NAN, 0.0).unwrap_err().contains("not finite"));
        let zero = Srt { scale: Vec3::ONE, rotation: Quat::from_xyzw(0.0, 0.0, 0.0, 0.0), translation: Vec3::ZERO };
        assert!(MotionTransform::new(MotionKeys::Srt(vec![zero, zero]), 0.0, 1.0).unwrap_err().contains("zero"));
    }

    /// Every sampled instant of a spinning, moving box lies in its bounds.
    #[test]
    fn bounds_hold_the_motion() {
        let child = OAabb::new(Vec3::new(1.0, -0.5, -0.5).into(), Vec3::new(2.0, 0.5, 0.5).into());
        let key = |angle: f32, x: f32| Srt {
            scale: Vec3::splat(1.0 + x),
            rotation: Quat::from_rotation_z(angle),
            translation: Vec3::new(x, 0.0, 0.0),
        };
        let m =
            MotionTransform::new(MotionKeys::Srt(vec![key(0.0, 0.0), key(2.5, 1.0), key(5.0, 3.0)]), 0.0, 1.0).unwrap();
        let b = m.bounds(&child);
        for s in 0..=200 {
            let inst = box_of(m.matrix_at(s as f32 / 200.0), &child);
            assert!(b.contains_point(inst.min) && b.contains_point(inst.max), "at {s}: {inst:?} not in {b:?}");
        }
    }
}
