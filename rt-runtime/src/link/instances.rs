//! Instances as programs see them (`instance_index()`, `instance_id()`):
//! every geometry instance a traced node reaches, once for every path down
//! to it, numbered depth first in child order (a geometry group's children,
//! a group's or a selector's children, every one of a selector's whether
//! its visit program chooses it or not, a transform's child). A node's
//! number of instances ([`Numbering::leaves`]) depends only on the graph
//! below it, so a path's first index is the sum, over the groups and
//! selectors it passes, of the instances of the children before the one it
//! takes ([`Numbering::offsets`]): what every traversal adds up as it
//! descends, the CPU backend's recursion, the compute kernel's stacks and
//! the ray-query side table alike. A hit's index is then its path's index
//! plus its geometry instance's place in the geometry group
//! ([`resolve`]).
//!
//! Ids are set on geometry instances and transforms
//! (`Context::set_instance_id`); a hit's is its geometry instance's, else
//! the innermost transform's with one on its path, else
//! [`INSTANCE_ID_NONE`].

use crate::error::Result;
use crate::scene::{NodeId, NodeKind, Scene};
pub(crate) use rt_abi::INSTANCE_ID_NONE;

/// A path down the graph to a geometry group: the instance index of the
/// group's first geometry instance, and the innermost instance id above it
/// ([`INSTANCE_ID_NONE`]: none).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct InstancePath {
    pub(crate) base: u32,
    pub(crate) id: u32,
}

impl InstancePath {
    /// The path of a traced node itself.
    pub(crate) const ROOT: InstancePath = InstancePath { base: 0, id: INSTANCE_ID_NONE };

    /// Down to a child whose instances start `offset` after this path's.
    pub(crate) fn child(self, offset: u32) -> InstancePath {
        InstancePath { base: self.base.wrapping_add(offset), ..self }
    }

    /// Through a transform (or chain of them) with instance id `id`.
    pub(crate) fn through(self, id: u32) -> InstancePath {
        if id == INSTANCE_ID_NONE { self } else { InstancePath { id, ..self } }
    }
}

/// How many instances each node reaches.
pub(crate) struct Numbering {
    leaves: Vec<u32>,
}

impl Numbering {
    /// Counts every node's instances (children before parents).
    pub(crate) fn of(scene: &Scene) -> Result<Numbering> {
        let mut leaves = vec![0u32; scene.nodes.len()];
        for n in crate::scene::nodes_post_order(scene)? {
            let count = match &scene.nodes[n.index() as usize].kind {
                NodeKind::GeometryGroup { children, .. } => children.len() as u32,
                NodeKind::Transform { child, .. } => leaves[child.index() as usize],
                NodeKind::Group { children, .. } | NodeKind::Selector { children, .. } => {
                    children.iter().fold(0u32, |sum, c| sum.wrapping_add(leaves[c.index() as usize]))
                }
            };
            leaves[n.index() as usize] = count;
        }
        Ok(Numbering { leaves })
    }

    /// The instances node `n` reaches.
    pub(crate) fn leaves(&self, n: NodeId) -> u32 {
        self.leaves[n.index() as usize]
    }

    /// Where each of `children`'s instances start, counted from their
    /// parent's first.
    pub(crate) fn offsets(&self, children: &[NodeId]) -> Vec<u32> {
        let mut at = 0u32;
        children
            .iter()
            .map(|c| {
                let o = at;
                at = at.wrapping_add(self.leaves(*c));
                o
            })
            .collect()
    }
}

/// The instance id of the chain of transforms from `top` down: its
/// innermost transform's with one ([`INSTANCE_ID_NONE`]: none), and the
/// node below the chain.
pub(crate) fn chain_id(scene: &Scene, top: NodeId) -> (u32, NodeId) {
    let mut id = INSTANCE_ID_NONE;
    let mut n = top;
    // Bounded: graphs with cycles are refused before any launch.
    for _ in 0..=scene.nodes.len() {
        let rec = &scene.nodes[n.index() as usize];
        let NodeKind::Transform { child, .. } = &rec.kind else { break };
        if rec.instance_id != INSTANCE_ID_NONE {
            id = rec.instance_id;
        }
        n = *child;
    }
    (id, n)
}

/// The instance index and id of geometry instance `gi` of geometry group
/// `group` reached by `path` (its first place in the group, where it is
/// listed twice). (The CPU backend's, not built for wasm32; the kernels
/// resolve it in WGSL, `rt_instance_of`.)
#[cfg(not(target_arch = "wasm32"))]
pub(crate) fn resolve(scene: &Scene, path: InstancePath, group: NodeId, gi: u32) -> (u32, u32) {
    let children = match &scene.nodes[group.index() as usize].kind {
        NodeKind::GeometryGroup { children, .. } => &children[..],
        _ => &[],
    };
    let k = children.iter().position(|c| c.index() == gi).unwrap_or(0) as u32;
    let own = scene.instances.get(gi as usize).map_or(INSTANCE_ID_NONE, |g| g.instance_id);
    let id = if own != INSTANCE_ID_NONE { own } else { path.id };
    (path.base.wrapping_add(k), id)
}

/// The words the compute kernel reads a geometry group's geometry
/// instances by (`rt_instance_of`): `[count, geometry instance.., their
/// ids..]`.
pub(crate) fn group_words(scene: &Scene, group: NodeId) -> Vec<u32> {
    let children = match &scene.nodes[group.index() as usize].kind {
        NodeKind::GeometryGroup { children, .. } => &children[..],
        _ => &[],
    };
    let mut words = vec![children.len() as u32];
    words.extend(children.iter().map(|c| c.index()));
    words.extend(children.iter().map(|c| scene.instances[c.index() as usize].instance_id));
    words
}
