//! Geometry: triangle meshes and custom primitives, and moving them
//! (new vertex positions, vertex motion keys).

use super::Context;
use crate::error::{Result, SceneError};
use crate::scene::*;
use crate::vars::VarScope;
use crate::vertex_motion::VertexMotion;
use rt_std::program::ProgramKind;

impl Context {
    /// Creates a triangle geometry; the mesh is checked first.
    pub fn create_triangles(&mut self, mesh: TriangleMesh) -> Result<GeometryId> {
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        let id = self.scene.geometries.len() as u32;
        mesh.validate().map_err(|problem| SceneError::BadGeometry { geometry: id, problem })?;
        self.scene.geometries.push(GeometryRec {
            kind: GeometryKind::Triangles(mesh),
            vars: VarScope::default(),
            vertex_motion: None,
        });
        Ok(GeometryId(id))
    }

    /// Creates custom geometry of `primitive_count` primitives, each
    /// intersected by `intersection` and bounded by `bounding_box`.
    pub fn create_custom_geometry(
        &mut self,
        primitive_count: u32,
        intersection: ProgramId,
        bounding_box: ProgramId,
    ) -> Result<GeometryId> {
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        self.expect_kind(intersection, ProgramKind::Intersection, "a custom geometry's intersection".into())?;
        self.expect_kind(bounding_box, ProgramKind::BoundingBox, "a custom geometry's bounding box".into())?;
        self.scene.geometries.push(GeometryRec {
            kind: GeometryKind::Custom { primitive_count, intersection, bounding_box },
            vars: VarScope::default(),
            vertex_motion: None,
        });
        Ok(GeometryId(self.scene.geometries.len() as u32 - 1))
    }

    /// Moves a triangle geometry's vertices (same count): accelerations over
    /// it are refit, not rebuilt, at the next launch. A geometry with vertex
    /// motion ([`set_motion_vertices`](Self::set_motion_vertices)) becomes
    /// static at these positions.
    pub fn set_triangle_positions(&mut self, g: GeometryId, positions: Vec<glam::Vec3>) -> Result<()> {
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        let (mesh, motion) = self.triangles_mut(g, "")?;
        if positions.len() != mesh.positions.len() {
            return Err(SceneError::BadGeometry {
                geometry: g.0,
                problem: format!(
                    "{} positions given for {} vertices; create a new geometry to change topology",
                    positions.len(),
                    mesh.positions.len()
                ),
            }
            .into());
        }
        // The rest of the mesh was checked when it was created; with the
        // same vertex count, only the positions themselves can be wrong.
        check_positions(&positions).map_err(|problem| SceneError::BadGeometry { geometry: g.0, problem })?;
        mesh.positions = positions;
        *motion = None;
        self.accels.geometry_moved(g.0);
        Ok(())
    }

    /// Gives triangle geometry `g` vertex motion: `keys` are two or more
    /// sets of vertex positions (the mesh's vertex count each, its indices
    /// over them) spread evenly over `[t0, t1]`. A ray traced at time `t`
    /// (`rt_trace_at`) meets each triangle with its vertices interpolated
    /// linearly between the two keys around `t`, clamped to the first and
    /// last key outside the range (OptiX's `RT_MOTIONBORDERMODE_CLAMP`).
    /// The built-in attributes (`geometric_normal`, `barycentrics`) are the
    /// interpolated triangle's; shading normals and texture coordinates stay
    /// per vertex. The mesh's positions become the first key's, and
    /// [`set_triangle_positions`](Self::set_triangle_positions) makes it
    /// static again.
    ///
    /// Triangles' boxes hold every key, so no instant's hit is lost. The
    /// ray-query traversal does not interpolate vertices: a scene with
    /// vertex motion runs on the compute traversal.
    #[doc(alias = "rtGeometryTrianglesSetMotionVertices")]
    #[doc(alias = "rtGeometryTrianglesSetMotionSteps")]
    #[doc(alias = "rtGeometryTrianglesSetMotionRange")]
    #[doc(alias = "rtGeometryTrianglesSetMotionBorderMode")]
    pub fn set_motion_vertices(&mut self, g: GeometryId, keys: Vec<Vec<glam::Vec3>>, t0: f32, t1: f32) -> Result<()> {
        let (mesh, held) = self.triangles_mut(g, ": vertex motion keys move triangles' vertices")?;
        let motion = VertexMotion::new(keys, t0, t1, mesh.positions.len())
            .map_err(|problem| SceneError::BadGeometry { geometry: g.0, problem })?;
        mesh.positions.clone_from(&motion.keys[0]);
        *held = Some(Box::new(motion));
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        self.accels.geometry_moved(g.0);
        Ok(())
    }

    /// Triangle geometry `g`'s mesh and vertex motion, to move its
    /// vertices; other geometry is refused as "not a triangle geometry"
    /// followed by `why`.
    fn triangles_mut(
        &mut self,
        g: GeometryId,
        why: &str,
    ) -> Result<(&mut TriangleMesh, &mut Option<Box<VertexMotion>>)> {
        let rec =
            self.scene.geometries.get_mut(g.0 as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{g:?}")))?;
        match rec {
            GeometryRec { kind: GeometryKind::Triangles(mesh), vertex_motion, .. } => Ok((mesh, vertex_motion)),
            _ => {
                Err(SceneError::BadGeometry { geometry: g.0, problem: format!("not a triangle geometry{why}") }.into())
            }
        }
    }

    /// Triangle geometry `g`'s vertex motion, if it has some.
    pub fn motion_vertices(&self, g: GeometryId) -> Option<&VertexMotion> {
        self.scene.geometries.get(g.0 as usize)?.vertex_motion.as_deref()
    }
}
