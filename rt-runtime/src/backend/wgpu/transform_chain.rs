//! Transform chains as the wgpu backend encodes them: the matrices along a
//! path composed in f64, and the composition inverted in f64, each rounded
//! to f32 once.
//!
//! The CPU backend transforms a ray level by level, each level by its own
//! inverse; the kernels take one object-to-world and one world-to-object
//! matrix per chain. Composed and inverted in f32, a chain of nearly
//! singular transforms (two z scales of 1e-3, a condition number near
//! 10^6) loses enough bits that rays grazing a squashed sphere hit on one
//! backend and miss on the other (the scene fuzzer's seed 7, graph 371,
//! `tests/tests/scene_fuzz.rs`). In f64 the rounding error of the chain is
//! that of its final rounding, as close as f32 can say.

use glam::{DMat4, Mat4};

/// The product of the transforms along a path, from the root down.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Chain(DMat4);

impl Chain {
    /// The empty chain.
    pub const IDENTITY: Chain = Chain(DMat4::IDENTITY);

    /// This chain followed (further down the path) by `m`.
    pub fn then(self, m: Mat4) -> Chain {
        Chain(self.0 * m.as_dmat4())
    }

    /// Object to world, rounded once.
    pub fn object_to_world(&self) -> Mat4 {
        self.0.as_mat4()
    }

    /// World to object: the chain inverted before it is rounded.
    pub fn world_to_object(&self) -> Mat4 {
        self.0.inverse().as_mat4()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// The fuzzer's case: two nearly singular transforms. Each entry of the
    /// f64 inverse, rounded, is within f32's rounding of the exact one;
    /// the f32 composition's inverse is not.
    #[test]
    fn a_nearly_singular_chain_is_inverted_as_close_as_f32_says() {
        let a = Mat4::from_scale_rotation_translation(
            Vec3::new(1.3, 0.7, 1e-3),
            glam::Quat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 0.7),
            Vec3::new(0.2, -0.4, 0.1),
        );
        let b = Mat4::from_scale_rotation_translation(
            Vec3::new(0.9, 1.7, 1.3e-3),
            glam::Quat::from_euler(glam::EulerRot::XYZ, -0.8, 0.4, 2.1),
            Vec3::new(-0.3, 0.5, 0.2),
        );
        let chain = Chain::IDENTITY.then(a).then(b);
        let exact = (a.as_dmat4() * b.as_dmat4()).inverse();
        let error = |m: Mat4| {
            let (m, e) = (m.to_cols_array(), exact.to_cols_array());
            let scale = e.iter().fold(0.0f64, |s, x| s.max(x.abs()));
            m.iter().zip(e).fold(0.0f64, |worst, (x, y)| worst.max((*x as f64 - y).abs() / scale))
        };
        let ours = error(chain.world_to_object());
        let f32s = error((a * b).inverse());
        assert!(ours <= f32::EPSILON as f64, "{ours:e}");
        assert!(f32s > 8.0 * f32::EPSILON as f64, "{f32s:e}");
        assert_eq!(chain.object_to_world(), (a.as_dmat4() * b.as_dmat4()).as_mat4());
    }
}
