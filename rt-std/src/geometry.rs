//! [`Aabb`]: what bounding-box programs return.

use glam::Vec3;

use crate::data::RtData;
use crate::layout::{FieldLayout, LayoutKind, ScalarKind, TypeLayout};

const VEC3: LayoutKind = LayoutKind::Vector { scalar: ScalarKind::F32, len: 3 };

/// An axis-aligned box from `min` to `max` (inclusive). A bounding-box
/// program returns one per primitive; a box with `min > max` on some axis is
/// empty. In WGSL it is the struct `RtAabb`, six packed words.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Aabb {
    /// The corner with the smallest coordinates.
    pub min: Vec3,
    /// The corner with the largest coordinates.
    pub max: Vec3,
}

impl Aabb {
    /// A box from its two corners.
    ///
    /// Program kinds: all.
    pub const fn new(min: Vec3, max: Vec3) -> Aabb {
        Aabb { min, max }
    }
}

impl RtData for Aabb {
    const LAYOUT: TypeLayout = TypeLayout {
        kind: crate::layout::LayoutKind::Builtin,
        rust: "Aabb",
        wgsl: "RtAabb",
        words: 6,
        fields: &[
            FieldLayout { name: "min", ty: "Vec3", kind: VEC3, offset_words: 0 },
            FieldLayout { name: "max", ty: "Vec3", kind: VEC3, offset_words: 3 },
        ],
    };

    fn write_words(&self, out: &mut [u32]) {
        self.min.write_words(&mut out[0..3]);
        self.max.write_words(&mut out[3..6]);
    }

    fn read_words(words: &[u32]) -> Self {
        Aabb { min: Vec3::read_words(&words[0..3]), max: Vec3::read_words(&words[3..6]) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aabb_round_trips_through_words() {
        let b = Aabb::new(Vec3::new(-1.0, -2.5, 0.0), Vec3::new(4.0, 1e9, -0.0));
        let mut words = [0u32; 6];
        b.write_words(&mut words);
        assert_eq!(words[4], 1e9f32.to_bits());
        assert_eq!(words[5], (-0.0f32).to_bits());
        let back = Aabb::read_words(&words);
        assert_eq!(back, b);
        assert!(back.max.z.is_sign_negative());
        assert_eq!(Aabb::LAYOUT.words, 6);
        assert_eq!(Aabb::LAYOUT.fields[1].offset_words, 3);
    }
}
