//! Acceleration structures: OptiX's builder names mapped onto obvhs.
//!
//! | builder | obvhs | why |
//! | --- | --- | --- |
//! | `Bvh` | BVH2, `medium_build` (PLOC + reinsertion) | the general-purpose default; refits |
//! | `Sbvh` | BVH2 from triangles, `slow_build` (spatial pre-splits) | highest quality; needs triangles |
//! | `MedianBvh` | BVH2, `fast_build` | fast build, lower quality |
//! | `Lbvh` | BVH2, `fastest_build` (PLOC, minimum search: Morton-order merging, like an LBVH) | fastest build |
//! | `TriangleKdTree` | — | obvhs builds no kd-trees: an error, not a silent remap |
//! | `NoAccel` | a single leaf holding every primitive | linear scan |

use glam::Vec3;
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb as OAabb;
use obvhs::bvh2::Bvh2;

/// An acceleration builder, by OptiX's names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Builder {
    Bvh,
    Sbvh,
    MedianBvh,
    Lbvh,
    TriangleKdTree,
    NoAccel,
}

impl Builder {
    pub fn name(self) -> &'static str {
        match self {
            Builder::Bvh => "Bvh",
            Builder::Sbvh => "Sbvh",
            Builder::MedianBvh => "MedianBvh",
            Builder::Lbvh => "Lbvh",
            Builder::TriangleKdTree => "TriangleKdTree",
            Builder::NoAccel => "NoAccel",
        }
    }

    /// Parses OptiX's builder names.
    pub fn from_name(name: &str) -> Option<Builder> {
        [Builder::Bvh, Builder::Sbvh, Builder::MedianBvh, Builder::Lbvh, Builder::TriangleKdTree, Builder::NoAccel]
            .into_iter()
            .find(|b| b.name() == name)
    }
}

/// An acceleration structure attached to a geometry group or group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Acceleration {
    pub builder: Builder,
}

impl Acceleration {
    pub fn new(builder: Builder) -> Self {
        Acceleration { builder }
    }
}

impl Default for Acceleration {
    fn default() -> Self {
        Acceleration::new(Builder::Bvh)
    }
}

/// A built BVH over primitives with known bounds.
pub(crate) struct Bvh {
    pub bvh: Bvh2,
}

pub(crate) fn to_oaabb(min: Vec3, max: Vec3) -> OAabb {
    OAabb::new(min.into(), max.into())
}

/// Builds a BVH over `bounds`; `triangles`, when every primitive is a
/// triangle, enables spatial splits for `Sbvh`.
pub(crate) fn build(
    builder: Builder,
    bounds: &[OAabb],
    triangles: Option<&[obvhs::triangle::Triangle]>,
) -> Result<Bvh, crate::RtError> {
    let mut t = std::time::Duration::ZERO;
    let bvh = match builder {
        Builder::TriangleKdTree => {
            return Err(crate::RtError::UnsupportedBuilder {
                builder: "TriangleKdTree",
                reason: "obvhs builds BVHs, not kd-trees; use Sbvh for the same trace quality",
            });
        }
        Builder::NoAccel => {
            let mut bvh = Bvh2::zeroed(bounds.len());
            let mut all = OAabb::empty();
            for b in bounds {
                all = all.union(b);
            }
            bvh.nodes = vec![obvhs::bvh2::node::Bvh2Node::new(all, bounds.len() as u32, 0)];
            bvh.primitive_indices = (0..bounds.len() as u32).collect();
            bvh
        }
        Builder::Sbvh => match triangles {
            Some(tris) => obvhs::bvh2::builder::build_bvh2_from_tris(tris, BvhBuildParams::slow_build(), &mut t),
            None => {
                return Err(crate::RtError::UnsupportedBuilder {
                    builder: "Sbvh",
                    reason: "spatial splits need triangles, and this group holds custom primitives or instances; use Bvh",
                });
            }
        },
        Builder::Bvh => obvhs::bvh2::builder::build_bvh2(bounds, BvhBuildParams::medium_build(), &mut t),
        Builder::MedianBvh => obvhs::bvh2::builder::build_bvh2(bounds, BvhBuildParams::fast_build(), &mut t),
        Builder::Lbvh => obvhs::bvh2::builder::build_bvh2(bounds, BvhBuildParams::fastest_build(), &mut t),
    };
    Ok(Bvh { bvh })
}

impl Bvh {
    /// Refits to new primitive bounds (same primitives, moved).
    pub fn refit(&mut self, bounds: &[OAabb]) {
        for node in self.bvh.nodes.iter_mut() {
            if node.is_leaf() {
                let mut b = OAabb::empty();
                for i in node.first_index..node.first_index + node.prim_count {
                    b = b.union(&bounds[self.bvh.primitive_indices[i as usize] as usize]);
                }
                node.set_aabb(b);
            }
        }
        self.bvh.refit_all();
    }

    /// Visits the primitives whose leaves the ray segment `(tmin, tmax())`
    /// enters, nearest leaves first; `visit` returns false to stop.
    /// `tmax` is re-read after every leaf so closer hits prune the search.
    pub fn traverse(&self, origin: Vec3, inv_dir: Vec3, tmin: f32, tmax: &dyn Fn() -> f32, visit: &mut dyn FnMut(u32) -> bool) {
        let nodes = &self.bvh.nodes;
        if nodes.is_empty() {
            return;
        }
        let hit = |n: &obvhs::bvh2::node::Bvh2Node, tmax: f32| -> f32 {
            let b = n.aabb();
            let t0 = (Vec3::from(b.min) - origin) * inv_dir;
            let t1 = (Vec3::from(b.max) - origin) * inv_dir;
            let near = t0.min(t1).max_element().max(tmin);
            let far = t0.max(t1).min_element().min(tmax);
            if near <= far { near } else { f32::INFINITY }
        };
        // (node, entry distance): a node is skipped if a closer hit was found
        // after it was pushed.
        let mut stack: [(u32, f32); 128] = [(0, 0.0); 128];
        let root = hit(&nodes[0], tmax());
        if root == f32::INFINITY {
            return;
        }
        stack[0] = (0, root);
        let mut sp = 1usize;
        while sp > 0 {
            sp -= 1;
            let (index, t) = stack[sp];
            if t > tmax() {
                continue;
            }
            let node = &nodes[index as usize];
            if node.is_leaf() {
                for i in node.first_index..node.first_index + node.prim_count {
                    if !visit(self.bvh.primitive_indices[i as usize]) {
                        return;
                    }
                }
                continue;
            }
            let (a, b) = (node.first_index, node.first_index + 1);
            let limit = tmax();
            let (ta, tb) = (hit(&nodes[a as usize], limit), hit(&nodes[b as usize], limit));
            // Push the far child first so the near one is visited first.
            let ((near, tn), (far, tf)) = if ta <= tb { ((a, ta), (b, tb)) } else { ((b, tb), (a, ta)) };
            for (n, t) in [(far, tf), (near, tn)] {
                if t != f32::INFINITY && sp < stack.len() {
                    stack[sp] = (n, t);
                    sp += 1;
                }
            }
        }
    }
}
