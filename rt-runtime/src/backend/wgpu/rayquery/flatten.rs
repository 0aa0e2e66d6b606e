//! The scene graph as ray queries see it: one level of instances per traced
//! root. Every path from a root through groups and transforms down to a
//! geometry group becomes one instance of the root's TLAS, with the
//! transforms along it multiplied and the visibility masks along it folded
//! into the instance's one 8-bit mask. A selector (whose visit program
//! chooses a child per ray) and a path whose masks no single mask can say
//! cannot be flattened: such scenes keep the compute traversal
//! ([`Unsupported`] says which node and why).

use crate::backend::wgpu::encode::{instances, kept_masks};
use crate::backend::wgpu::transform_chain::Chain;
use crate::error::Result;
use crate::link::instances::{InstancePath, Numbering};
use crate::scene::{GeometryId, GeometryKind, NodeId, NodeKind, Scene};
use crate::vars::{VarScope, VarValue};
use glam::Mat4;

/// One instance of a root's TLAS.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct FlatInstance {
    /// The geometry group (its BLAS).
    pub group: NodeId,
    /// The compute traversal's instance record of that group, which the
    /// kernel finds the hit's geometry instances through (the TLAS
    /// instance's custom data: `record * 2 + part`).
    pub record: u32,
    /// Object to world along the path.
    pub object_to_world: Mat4,
    /// The one mask a ray's mask must share a bit with.
    pub mask: u8,
    /// The path's instance index and id (`instance_index()`).
    pub path: InstancePath,
}

/// Why a scene keeps the compute traversal.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Unsupported {
    /// A selector's visit program chooses a child per ray.
    Selector(NodeId),
    /// The masks along the path to a node share no single mask.
    Masks { node: NodeId, masks: Vec<u8> },
    /// No variable holds a node to trace.
    NoRoots,
    /// A motion transform's matrix depends on the ray's time.
    Motion(NodeId),
    /// A geometry group holds triangles whose vertices move with the ray's
    /// time.
    VertexMotion { group: NodeId, geometry: GeometryId },
}

impl std::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Unsupported::Selector(n) => write!(
                f,
                "node {} is a selector, whose visit program chooses a child per ray; ray queries walk one level of instances",
                n.index()
            ),
            Unsupported::Masks { node, masks } => write!(
                f,
                "the path to node {} has visibility masks {masks:02x?}, which no one 8-bit instance mask says",
                node.index()
            ),
            Unsupported::NoRoots => write!(f, "no variable holds a node (`Object`) to trace"),
            Unsupported::Motion(n) => write!(
                f,
                "node {} is a motion transform, whose matrix depends on each ray's time; an instance of an acceleration structure has one matrix",
                n.index()
            ),
            Unsupported::VertexMotion { group, geometry } => write!(
                f,
                "geometry group {} holds geometry {}, whose vertices move with each ray's time; a triangle acceleration structure holds fixed vertices",
                group.index(),
                geometry.index()
            ),
        }
    }
}

/// The flattened scene: its roots (the nodes programs trace, from their
/// `Object` variables) and each root's instances.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Flat {
    pub roots: Vec<(NodeId, Vec<FlatInstance>)>,
    /// How many instance records the compute encoding has (the kernel's
    /// side table holds two words for each).
    pub records: u32,
}

/// The nodes that variables in any scope hold, in first-seen order.
pub(crate) fn roots(scene: &Scene) -> Vec<NodeId> {
    let mut scopes: Vec<&VarScope> = vec![&scene.vars];
    scopes.extend(scene.programs.iter().map(|p| &p.vars));
    scopes.extend(scene.geometries.iter().map(|g| &g.vars));
    scopes.extend(scene.materials.iter().map(|m| &m.vars));
    scopes.extend(scene.instances.iter().map(|i| &i.vars));
    scopes.extend(scene.nodes.iter().map(|n| &n.vars));
    let mut roots = Vec::new();
    for scope in scopes {
        for name in scope.names() {
            if let Some(VarValue::Object(n)) = scope.get(name)
                && (n.index() as usize) < scene.nodes.len()
                && !roots.contains(n)
            {
                roots.push(*n);
            }
        }
    }
    roots
}

/// Flattens every root of `scene`; `Ok(Err(..))` when it cannot be.
pub(crate) fn flatten(scene: &Scene) -> Result<std::result::Result<Flat, Unsupported>> {
    let (instance_of_node, records) = instances(scene)?;
    let roots = roots(scene);
    if roots.is_empty() {
        return Ok(Err(Unsupported::NoRoots));
    }
    let numbering = Numbering::of(scene)?;
    let mut flat = Flat { roots: Vec::new(), records: records.len() as u32 };
    for root in roots {
        let mut out = Vec::new();
        let mut stack: Vec<(NodeId, Chain, Vec<u8>, InstancePath)> =
            vec![(root, Chain::IDENTITY, Vec::new(), InstancePath::ROOT)];
        // Depth is bounded: `plan` refused cycles.
        while let Some((n, m, mut masks, path)) = stack.pop() {
            let rec = &scene.nodes[n.index() as usize];
            masks.push(rec.visibility_mask);
            match &rec.kind {
                NodeKind::GeometryGroup { children, .. } => {
                    if children.is_empty() {
                        continue;
                    }
                    let moving = children
                        .iter()
                        .map(|gi| scene.instances[gi.index() as usize].geometry)
                        .find(|g| scene.geometries[g.index() as usize].vertex_motion.is_some());
                    if let Some(geometry) = moving {
                        return Ok(Err(Unsupported::VertexMotion { group: n, geometry }));
                    }
                    let Some(mask) = one_mask(&masks) else {
                        return Ok(Err(Unsupported::Masks { node: n, masks }));
                    };
                    let record = instance_of_node[n.index() as usize].expect("a geometry group is an instance");
                    out.push(FlatInstance { group: n, record, object_to_world: m.object_to_world(), mask, path });
                }
                NodeKind::Group { children, .. } => {
                    // Reversed, so that instances come out in child order.
                    let offsets = numbering.offsets(children);
                    stack
                        .extend(children.iter().zip(offsets).rev().map(|(c, o)| (*c, m, masks.clone(), path.child(o))));
                }
                NodeKind::Transform { motion: Some(_), .. } => return Ok(Err(Unsupported::Motion(n))),
                NodeKind::Transform { matrix, child, .. } => {
                    stack.push((*child, m.then(*matrix), masks, path.through(rec.instance_id)))
                }
                NodeKind::Selector { .. } => return Ok(Err(Unsupported::Selector(n))),
            }
        }
        flat.roots.push((root, out));
    }
    Ok(Ok(flat))
}

/// The one mask that says "shares a bit with each of `masks`", if there is
/// one: masks containing another are implied by it (as in the compute
/// traversal's visibility words), so one mask must remain.
fn one_mask(masks: &[u8]) -> Option<u8> {
    match kept_masks(masks)[..] {
        [] => Some(0xff),
        [m] => Some(m),
        _ => None,
    }
}

/// The parts of geometry group `group`'s BLAS: its triangle geometry
/// instances (part 0) and its custom-primitive ones (part 1), as global
/// geometry instance indices in child order.
pub(crate) fn parts(scene: &Scene, group: NodeId) -> [Vec<u32>; 2] {
    let mut parts = [Vec::new(), Vec::new()];
    if let NodeKind::GeometryGroup { children, .. } = &scene.nodes[group.index() as usize].kind {
        for gi in children {
            let g = scene.instances[gi.index() as usize].geometry;
            let part = match scene.geometries[g.index() as usize].kind {
                GeometryKind::Triangles(_) => 0,
                GeometryKind::Custom { .. } => 1,
            };
            parts[part].push(gi.index());
        }
    }
    parts
}

#[cfg(test)]
mod tests {
    use super::one_mask;

    #[test]
    fn masks_fold_into_one_where_one_says_them() {
        assert_eq!(one_mask(&[0xff, 0xff]), Some(0xff));
        assert_eq!(one_mask(&[0xff, 0x03, 0xff]), Some(0x03));
        // 0x01 within 0x03: a ray sharing a bit with 0x01 shares one with 0x03.
        assert_eq!(one_mask(&[0x03, 0x01]), Some(0x01));
        assert_eq!(one_mask(&[0x01, 0x02]), None);
    }
}
