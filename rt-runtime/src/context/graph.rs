//! The scene graph above geometry: materials and their hit programs,
//! geometry instances, geometry groups, groups, transforms (static and in
//! motion), selectors, visibility masks and instance ids.

use super::Context;
use crate::accel::Acceleration;
use crate::error::{Result, SceneError};
use crate::motion::{MotionKeys, MotionTransform};
use crate::scene::*;
use crate::vars::VarScope;
use glam::Mat4;
use rt_std::program::ProgramKind;

impl Context {
    /// A material without programs: set its closest- and any-hit programs per
    /// ray type, and its variables (the material scope).
    pub fn create_material(&mut self) -> MaterialId {
        self.scene.structure_version += 1;
        let n = self.ray_type_count() as usize;
        self.scene.materials.push(MaterialRec {
            closest_hit: vec![None; n],
            any_hit: vec![None; n],
            vars: VarScope::default(),
        });
        MaterialId(self.scene.materials.len() as u32 - 1)
    }

    fn material_mut(&mut self, m: MaterialId) -> Result<&mut MaterialRec> {
        self.scene.materials.get_mut(m.0 as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{m:?}")).into())
    }

    /// Sets material `m`'s closest-hit program for `ray_type`: it runs once
    /// per ray, at the nearest hit accepted.
    pub fn set_closest_hit_program(&mut self, m: MaterialId, ray_type: u32, p: ProgramId) -> Result<()> {
        self.scene.structure_version += 1;
        self.check_ray_type(ray_type)?;
        self.expect_kind(p, ProgramKind::ClosestHit, format!("ray type {ray_type}'s closest hit"))?;
        self.material_mut(m)?.closest_hit[ray_type as usize] = Some(p);
        Ok(())
    }

    /// Sets material `m`'s any-hit program for `ray_type`: it runs at every
    /// hit found closer than the nearest so far, and may ignore it or end the
    /// ray.
    pub fn set_any_hit_program(&mut self, m: MaterialId, ray_type: u32, p: ProgramId) -> Result<()> {
        self.scene.structure_version += 1;
        self.check_ray_type(ray_type)?;
        self.expect_kind(p, ProgramKind::AnyHit, format!("ray type {ray_type}'s any hit"))?;
        self.material_mut(m)?.any_hit[ray_type as usize] = Some(p);
        Ok(())
    }

    /// Geometry `g` with its materials (at least one; a triangle's material
    /// index chooses among them).
    pub fn create_geometry_instance(&mut self, g: GeometryId, materials: &[MaterialId]) -> Result<GeometryInstanceId> {
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        if g.0 as usize >= self.scene.geometries.len() {
            return Err(SceneError::InvalidHandle(format!("{g:?}")).into());
        }
        if let Some(m) = materials.iter().find(|m| m.0 as usize >= self.scene.materials.len()) {
            return Err(SceneError::InvalidHandle(format!("{m:?}")).into());
        }
        if materials.is_empty() {
            return Err(SceneError::BadGeometry {
                geometry: g.0,
                problem: "a geometry instance needs at least one material".into(),
            }
            .into());
        }
        self.scene.instances.push(GeometryInstanceRec {
            geometry: g,
            materials: materials.to_vec(),
            vars: VarScope::default(),
            instance_id: rt_abi::INSTANCE_ID_NONE,
        });
        Ok(GeometryInstanceId(self.scene.instances.len() as u32 - 1))
    }

    fn push_node(&mut self, kind: NodeKind) -> NodeId {
        self.scene.structure_version += 1;
        self.scene.nodes.push(NodeRec {
            kind,
            visibility_mask: 0xff,
            vars: VarScope::default(),
            instance_id: rt_abi::INSTANCE_ID_NONE,
        });
        NodeId(self.scene.nodes.len() as u32 - 1)
    }

    fn check_nodes(&self, nodes: &[NodeId]) -> Result<()> {
        match nodes.iter().find(|n| n.0 as usize >= self.scene.nodes.len()) {
            Some(n) => Err(SceneError::InvalidHandle(format!("{n:?}")).into()),
            None => Ok(()),
        }
    }

    /// A node holding geometry instances, with the acceleration structure
    /// built over their primitives.
    pub fn create_geometry_group(&mut self, children: &[GeometryInstanceId], accel: Acceleration) -> Result<NodeId> {
        self.scene.structure_version += 1;
        self.scene.geometry_version += 1;
        if let Some(c) = children.iter().find(|c| c.0 as usize >= self.scene.instances.len()) {
            return Err(SceneError::InvalidHandle(format!("{c:?}")).into());
        }
        Ok(self.push_node(NodeKind::GeometryGroup { children: children.to_vec(), accel }))
    }

    /// A node holding other nodes, with the acceleration structure built over
    /// their bounds.
    pub fn create_group(&mut self, children: &[NodeId], accel: Acceleration) -> Result<NodeId> {
        self.check_nodes(children)?;
        Ok(self.push_node(NodeKind::Group { children: children.to_vec(), accel }))
    }

    /// A transform node; its inverse is computed here.
    pub fn create_transform(&mut self, matrix: Mat4, child: NodeId) -> Result<NodeId> {
        self.check_nodes(&[child])?;
        let inverse = checked_inverse(matrix)?;
        Ok(self.push_node(NodeKind::Transform { matrix, inverse, child, motion: None }))
    }

    /// A motion transform node: `keys` (two or more) spread evenly over the
    /// time range `[t0, t1]`, the transform at a ray's time
    /// ([`rt_trace_at`](rt_std::rt_trace_at)) interpolated between the two
    /// keys around it (matrices element by element, [`Srt`](crate::Srt)
    /// keys with their rotations slerped), clamped to the first and last
    /// key outside the range (OptiX's `RT_MOTIONBORDERMODE_CLAMP`, its
    /// default). Groups above bound the child over the whole motion
    /// ([`MotionTransform::bounds`](crate::MotionTransform)). An instant at
    /// which the interpolated matrix is singular hides the child.
    ///
    /// The ray-query traversal does not walk motion transforms: a scene
    /// with one runs on the compute traversal.
    #[doc(alias = "rtTransformSetMotionKeys")]
    #[doc(alias = "rtTransformSetMotionRange")]
    #[doc(alias = "rtTransformSetMotionBorderMode")]
    pub fn create_motion_transform(&mut self, keys: MotionKeys, t0: f32, t1: f32, child: NodeId) -> Result<NodeId> {
        self.check_nodes(&[child])?;
        let node = NodeId(self.scene.nodes.len() as u32);
        let motion = motion_keys(node, keys, t0, t1)?;
        let (matrix, inverse) = first_key(&motion);
        Ok(self.push_node(NodeKind::Transform { matrix, inverse, child, motion: Some(Box::new(motion)) }))
    }

    /// Gives transform `node` motion keys (as
    /// [`create_motion_transform`](Self::create_motion_transform));
    /// [`set_transform`](Self::set_transform) makes it static again.
    #[doc(alias = "rtTransformSetMotionKeys")]
    pub fn set_motion_keys(&mut self, node: NodeId, keys: MotionKeys, t0: f32, t1: f32) -> Result<()> {
        let motion = motion_keys(node, keys, t0, t1)?;
        self.scene.structure_version += 1;
        match self.scene.nodes.get_mut(node.0 as usize).map(|n| &mut n.kind) {
            Some(NodeKind::Transform { matrix, inverse, motion: m, .. }) => {
                (*matrix, *inverse) = first_key(&motion);
                *m = Some(Box::new(motion));
                self.accels.transform_moved();
                Ok(())
            }
            _ => Err(SceneError::InvalidHandle(format!("{node:?} (not a transform)")).into()),
        }
    }

    /// Transform `node`'s motion, if it has one.
    pub fn motion_keys(&self, node: NodeId) -> Option<&MotionTransform> {
        match self.scene.nodes.get(node.0 as usize).map(|n| &n.kind) {
            Some(NodeKind::Transform { motion, .. }) => motion.as_deref(),
            _ => None,
        }
    }

    /// Changes a transform's matrix (a refit of the groups above it).
    pub fn set_transform(&mut self, node: NodeId, matrix: Mat4) -> Result<()> {
        self.scene.structure_version += 1;
        let inv = checked_inverse(matrix)?;
        match self.scene.nodes.get_mut(node.0 as usize).map(|n| &mut n.kind) {
            Some(NodeKind::Transform { matrix: m, inverse, motion, .. }) => {
                *m = matrix;
                *inverse = inv;
                *motion = None;
                self.accels.transform_moved();
                Ok(())
            }
            _ => Err(SceneError::InvalidHandle(format!("{node:?} (not a transform)")).into()),
        }
    }

    /// A node whose `visit` program chooses, per ray, which of `children`
    /// the ray enters.
    pub fn create_selector(&mut self, visit: ProgramId, children: &[NodeId]) -> Result<NodeId> {
        self.expect_kind(visit, ProgramKind::Visit, "a selector's visit".into())?;
        self.check_nodes(children)?;
        Ok(self.push_node(NodeKind::Selector { visit, children: children.to_vec() }))
    }

    /// Rays trace into `node` only if their mask shares a bit with this.
    pub fn set_visibility_mask(&mut self, node: NodeId, mask: u8) -> Result<()> {
        self.scene.structure_version += 1;
        let n =
            self.scene.nodes.get_mut(node.0 as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{node:?}")))?;
        n.visibility_mask = mask;
        Ok(())
    }

    /// Gives the instances below `target` the id `instance_id()` returns
    /// on their hits (OptiX 7's `OptixInstance::instanceId`): `target` is a
    /// geometry instance, or a transform (every geometry instance below it).
    /// A hit's id is its geometry instance's own, else that of the
    /// innermost transform with one on the traced path, else
    /// [`INSTANCE_ID_NONE`](rt_std::INSTANCE_ID_NONE), which also clears an
    /// id. See [`rt_std::instance_index`] for what an instance is.
    #[doc(alias = "instanceId")]
    pub fn set_instance_id(&mut self, target: impl Into<Scope>, id: u32) -> Result<()> {
        let target = target.into();
        let slot = match target {
            Scope::GeometryInstance(gi) => self.scene.instances.get_mut(gi.0 as usize).map(|g| &mut g.instance_id),
            Scope::Node(n) => match self.scene.nodes.get_mut(n.0 as usize) {
                Some(rec @ NodeRec { kind: NodeKind::Transform { .. }, .. }) => Some(&mut rec.instance_id),
                Some(_) => {
                    return Err(SceneError::InvalidHandle(format!(
                        "{n:?} (not a transform: instance ids are set on geometry instances and transforms)"
                    ))
                    .into());
                }
                None => None,
            },
            _ => {
                return Err(SceneError::InvalidHandle(format!(
                    "{target:?} (instance ids are set on geometry instances and transforms)"
                ))
                .into());
            }
        };
        *slot.ok_or_else(|| SceneError::InvalidHandle(format!("{target:?}")))? = id;
        self.scene.structure_version += 1;
        Ok(())
    }

    /// The id set on a geometry instance or transform
    /// ([`set_instance_id`](Self::set_instance_id);
    /// [`INSTANCE_ID_NONE`](rt_std::INSTANCE_ID_NONE) when none is).
    pub fn instance_id(&self, target: impl Into<Scope>) -> Result<u32> {
        let target = target.into();
        let id = match target {
            Scope::GeometryInstance(gi) => self.scene.instances.get(gi.0 as usize).map(|g| g.instance_id),
            Scope::Node(n) => self.scene.nodes.get(n.0 as usize).map(|r| r.instance_id),
            _ => None,
        };
        id.ok_or_else(|| SceneError::InvalidHandle(format!("{target:?}")).into())
    }
}

/// Checked motion keys, or an error naming transform `node`.
fn motion_keys(node: NodeId, keys: MotionKeys, t0: f32, t1: f32) -> Result<MotionTransform> {
    MotionTransform::new(keys, t0, t1).map_err(|problem| {
        SceneError::BadTransform { problem: format!("transform {}: {problem}", node.index()) }.into()
    })
}

/// The first key's matrix and its inverse (identity where it has none): what
/// the scene keeps as a motion transform's static matrix.
fn first_key(motion: &MotionTransform) -> (Mat4, Mat4) {
    let m = motion.matrix_at(motion.t0);
    (m, checked_inverse(m).unwrap_or(Mat4::IDENTITY))
}

fn checked_inverse(m: Mat4) -> Result<Mat4> {
    let det = m.determinant();
    if !det.is_finite() || det.abs() < 1e-12 || !m.is_finite() {
        return Err(SceneError::BadTransform { problem: format!("the matrix is singular or not finite: {m:?}") }.into());
    }
    Ok(m.inverse())
}
