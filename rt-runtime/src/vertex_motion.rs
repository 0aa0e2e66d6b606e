//! Triangle meshes with vertex motion keys (OptiX 6's
//! `rtGeometryTrianglesSetMotionVertices`, `..SetMotionSteps`,
//! `..SetMotionRange`, `..SetMotionBorderMode` with
//! `RT_MOTIONBORDERMODE_CLAMP`): two or more sets of vertex positions
//! spread evenly over a time range; a ray at time `t` meets each triangle
//! with its vertices interpolated linearly between the two keys around `t`.
//!
//! The arithmetic here is the reference: the CPU backend calls it, and the
//! compute traversal's `rt_tri_corner` (`backend/wgpu/prelude.wgsl`) does
//! the same steps on the words `VertexMotion::encode` writes. Both
//! backends walk trees whose triangle boxes hold every key
//! (`VertexMotion::triangle_bounds`), so no instant's triangle lies
//! outside them.

use crate::motion::{check_range, segment};
use glam::Vec3;

/// A triangle mesh's motion: its vertex positions at each of two or more
/// keys, spread evenly over `[t0, t1]` and clamped outside it.
#[doc(alias = "rtGeometryTrianglesSetMotionVertices")]
#[derive(Clone, Debug, PartialEq)]
pub struct VertexMotion {
    /// Per key, a position per vertex (the mesh's vertex count each).
    pub keys: Vec<Vec<Vec3>>,
    /// The time of the first key.
    pub t0: f32,
    /// The time of the last key.
    pub t1: f32,
}

impl VertexMotion {
    /// Checks the keys against a mesh of `vertex_count` vertices: at least
    /// two keys, each a finite position per vertex, and a finite range with
    /// `t0 <= t1`.
    pub fn new(keys: Vec<Vec<Vec3>>, t0: f32, t1: f32, vertex_count: usize) -> Result<VertexMotion, String> {
        if keys.len() < 2 {
            return Err(format!("vertex motion needs at least 2 keys, found {}", keys.len()));
        }
        check_range(t0, t1)?;
        for (k, key) in keys.iter().enumerate() {
            if key.len() != vertex_count {
                return Err(format!("motion key {k} has {} positions for {vertex_count} vertices", key.len()));
            }
            if let Some(i) = key.iter().position(|p| !p.is_finite()) {
                return Err(format!("motion key {k}: vertex {i} has a non-finite position {:?}", key[i]));
            }
        }
        Ok(VertexMotion { keys, t0, t1 })
    }

    /// The vertices of the triangle of vertex indices `indices` (a
    /// triangle of the mesh these keys move) at `time`.
    #[inline]
    pub fn triangle_at(&self, indices: [u32; 3], time: f32) -> [Vec3; 3] {
        let (k, f) = segment(self.keys.len(), self.t0, self.t1, time);
        let (a, b) = (&self.keys[k], &self.keys[k + 1]);
        indices.map(|i| a[i as usize] * (1.0 - f) + b[i as usize] * f)
    }

    /// A box holding the triangle of vertex indices `indices` at every
    /// time: each vertex moves along straight segments between its keys,
    /// so the keys' boxes hold it.
    pub(crate) fn triangle_bounds(&self, indices: [u32; 3]) -> (Vec3, Vec3) {
        let mut lo = Vec3::INFINITY;
        let mut hi = Vec3::NEG_INFINITY;
        for key in &self.keys {
            for i in indices {
                let p = key[i as usize];
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        (lo, hi)
    }

    /// The words the compute traversal reads (`rt_tri_corner`): `[key
    /// count, vertex count, t0, t1]`, then each key's positions, three
    /// words a vertex.
    pub(crate) fn encode(&self, out: &mut Vec<u32>) {
        let vertices = self.keys.first().map_or(0, Vec::len);
        out.extend([self.keys.len() as u32, vertices as u32, self.t0.to_bits(), self.t1.to_bits()]);
        for key in &self.keys {
            out.extend(key.iter().flat_map(|p| p.to_array().map(f32::to_bits)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The triangle (0, 0, 0), (1, 0, 0), (0, 1, 0) raised to each height.
    fn rising(heights: &[f32]) -> Vec<Vec<Vec3>> {
        heights.iter().map(|&z| [Vec3::ZERO, Vec3::X, Vec3::Y].iter().map(|p| *p + Vec3::Z * z).collect()).collect()
    }

    #[test]
    fn vertices_interpolate_between_keys_and_clamp() {
        let m = VertexMotion::new(rising(&[0.0, 2.0, 6.0]), 1.0, 3.0, 3).unwrap();
        let z = |time: f32| m.triangle_at([0, 1, 2], time).map(|p| p.z);
        assert_eq!(z(1.0), [0.0; 3]);
        assert_eq!(z(1.5), [1.0; 3]);
        assert_eq!(z(2.0), [2.0; 3]);
        assert_eq!(z(2.5), [4.0; 3]);
        assert_eq!(z(3.0), [6.0; 3]);
        assert_eq!(z(-10.0), [0.0; 3]);
        assert_eq!(z(10.0), [6.0; 3]);
        assert_eq!(z(f32::NAN), [0.0; 3]);
        assert_eq!(m.triangle_at([0, 1, 2], 2.5)[1], Vec3::new(1.0, 0.0, 4.0));
    }

    #[test]
    fn bounds_hold_every_instant() {
        let mut keys = rising(&[0.0, 3.0]);
        keys[1][1] = Vec3::new(-2.0, 5.0, 3.0);
        let m = VertexMotion::new(keys, 0.0, 1.0, 3).unwrap();
        let (lo, hi) = m.triangle_bounds([0, 1, 2]);
        assert_eq!((lo, hi), (Vec3::new(-2.0, 0.0, 0.0), Vec3::new(1.0, 5.0, 3.0)));
        for s in 0..=100 {
            for p in m.triangle_at([0, 1, 2], s as f32 / 100.0) {
                assert!(p.cmpge(lo).all() && p.cmple(hi).all(), "{p} outside {lo}..{hi}");
            }
        }
    }

    #[test]
    fn bad_keys_are_refused() {
        let err = |keys, t0, t1| VertexMotion::new(keys, t0, t1, 3).unwrap_err();
        assert_eq!(err(rising(&[0.0]), 0.0, 1.0), "vertex motion needs at least 2 keys, found 1");
        assert_eq!(err(rising(&[0.0, 1.0]), 1.0, 0.0), "the motion range [1, 0] ends before it begins");
        let mut short = rising(&[0.0, 1.0]);
        short[1].pop();
        assert_eq!(err(short, 0.0, 1.0), "motion key 1 has 2 positions for 3 vertices");
        let mut nan = rising(&[0.0, 1.0, 2.0]);
        nan[2][1].y = f32::NAN;
        assert_eq!(err(nan, 0.0, 1.0), "motion key 2: vertex 1 has a non-finite position Vec3(1.0, NaN, 2.0)");
    }
}
