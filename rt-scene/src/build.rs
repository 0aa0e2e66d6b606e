//! Loaded files into a context's scene graph.
//!
//! Every mesh becomes one `Geometry` (its primitives merged, a material
//! index per triangle), one `GeometryInstance` over its materials and one
//! `GeometryGroup` (one BVH); each node that shows it adds a `Transform`
//! (its world matrix) over that same group, under one top `Group`. So a
//! mesh used by several nodes is built once and instanced, and traversal
//! is always two levels deep, however deep the file's hierarchy: world
//! matrices are composed here, once, rather than nested `Transform`s
//! composed on every ray.

use crate::error::SceneError;
use crate::gltf::Asset;
use crate::obj::LoadedMesh;
use crate::{Animation, Loaded, MaterialInfo, SceneInfo, Texture};
use glam::{Mat4, Vec3, Vec4};
use rt_runtime::{Acceleration, Builder, Context, MaterialId, RtError, SamplerId};
use rt_std::{FilterMode, WrapMode};

/// Adds `asset` to `ctx`; `file` names it in errors.
pub fn build_gltf(ctx: &mut Context, asset: Asset, file: &str) -> Result<Loaded, SceneError> {
    let rt = |error: RtError| SceneError::Runtime { file: file.to_string(), error: Box::new(error) };
    let mut materials = Materials::new(asset.materials, file);
    let mut groups = Vec::new();
    let (mut min, mut max) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    let mut triangles = 0;
    for data in &asset.meshes {
        let ids = data.materials.iter().map(|m| materials.id(ctx, *m)).collect::<Result<Vec<_>, _>>()?;
        let geometry = ctx.create_triangles(data.mesh.clone()).map_err(rt)?;
        let instance = ctx.create_geometry_instance(geometry, &ids).map_err(rt)?;
        groups.push(ctx.create_geometry_group(&[instance], Acceleration::new(Builder::Bvh)).map_err(rt)?);
    }
    let mut children = Vec::new();
    // Instances under animated nodes get a transform the animation moves.
    let moved: Vec<bool> =
        asset.rig.paths.iter().map(|p| asset.rig.channels.iter().any(|c| p.contains(&c.node))).collect();
    let mut transforms = Vec::new();
    for (i, &(mesh, world)) in asset.instances.iter().enumerate() {
        let data = &asset.meshes[mesh];
        triangles += data.mesh.indices.len();
        for p in &data.mesh.positions {
            let q = world.transform_point3(*p);
            min = min.min(q);
            max = max.max(q);
        }
        let node = if world == Mat4::IDENTITY && !moved[i] {
            groups[mesh]
        } else {
            ctx.create_transform(world, groups[mesh])
                .map_err(|e| SceneError::Runtime { file: file.to_string(), error: Box::new(e) })?
        };
        transforms.push(moved[i].then_some(node));
        children.push(node);
    }
    let animation = asset.rig.time_range().filter(|_| moved.contains(&true)).map(|(start, end)| Animation {
        rig: asset.rig.clone(),
        transforms,
        start,
        end,
        file: file.to_string(),
    });
    let top = ctx.create_group(&children, Acceleration::new(Builder::Bvh)).map_err(rt)?;
    let info = SceneInfo {
        meshes: asset.meshes.len(),
        instances: asset.instances.len(),
        triangles,
        unique_triangles: asset.meshes.iter().map(|m| m.mesh.indices.len()).sum(),
        min,
        max,
        camera: asset.camera,
        lights: asset.lights,
        warnings: asset.warnings,
    };
    Ok(Loaded { top, materials: materials.done(), info, animation })
}

/// Adds a loaded OBJ to `ctx`: one geometry group, no transform.
pub fn build_obj(ctx: &mut Context, loaded: LoadedMesh, file: &str) -> Result<Loaded, SceneError> {
    let rt = |error: RtError| SceneError::Runtime { file: file.to_string(), error: Box::new(error) };
    let infos = loaded.materials.iter().map(MaterialInfo::from_obj).collect();
    let mut materials = Materials::new(infos, file);
    let ids = (0..loaded.materials.len()).map(|i| materials.id(ctx, Some(i))).collect::<Result<Vec<_>, _>>()?;
    let triangles = loaded.mesh.indices.len();
    let geometry = ctx.create_triangles(loaded.mesh).map_err(rt)?;
    let instance = ctx.create_geometry_instance(geometry, &ids).map_err(rt)?;
    let top = ctx.create_geometry_group(&[instance], Acceleration::new(Builder::Bvh)).map_err(rt)?;
    let info = SceneInfo {
        meshes: 1,
        instances: 1,
        triangles,
        unique_triangles: triangles,
        min: loaded.min,
        max: loaded.max,
        camera: None,
        lights: Vec::new(),
        warnings: loaded.warnings,
    };
    Ok(Loaded { top, materials: materials.done(), info, animation: None })
}

/// The context's materials, made on first use, with the standard
/// variables set ([`crate::Material`]).
struct Materials {
    file: String,
    infos: Vec<MaterialInfo>,
    made: Vec<Option<MaterialId>>,
    default: Option<MaterialId>,
    white: Option<SamplerId>,
    out: Vec<crate::Material>,
}

impl Materials {
    fn new(infos: Vec<MaterialInfo>, file: &str) -> Self {
        Materials {
            file: file.to_string(),
            made: vec![None; infos.len()],
            infos,
            default: None,
            white: None,
            out: Vec::new(),
        }
    }

    /// The material for glTF material `index` (`None`: the default one).
    fn id(&mut self, ctx: &mut Context, index: Option<usize>) -> Result<MaterialId, SceneError> {
        self.make(ctx, index).map_err(|error| SceneError::Runtime { file: self.file.clone(), error })
    }

    fn make(&mut self, ctx: &mut Context, index: Option<usize>) -> Result<MaterialId, Box<RtError>> {
        if let Some(id) = index.and_then(|i| self.made[i]).or(if index.is_none() { self.default } else { None }) {
            return Ok(id);
        }
        // Each material is made once: its info (its texels, perhaps
        // hundreds of MiB) moves into the output rather than being copied.
        let info = index.map_or_else(MaterialInfo::default, |i| std::mem::take(&mut self.infos[i]));
        let id = ctx.create_material();
        let texture = match &info.base_color_texture {
            Some(t) => ctx.create_sampler(t.texels.clone(), t.width, t.height, WrapMode::Repeat, FilterMode::Linear)?,
            None => match self.white {
                Some(w) => w,
                None => {
                    let w = ctx.create_sampler(vec![Vec4::ONE], 1, 1, WrapMode::Repeat, FilterMode::Nearest)?;
                    self.white = Some(w);
                    w
                }
            },
        };
        ctx.set_var(id, "base_color", info.base_color.truncate())?;
        ctx.set_var(id, "base_color_texture", texture)?;
        ctx.set_var(id, "metallic", info.metallic)?;
        ctx.set_var(id, "roughness", info.roughness)?;
        ctx.set_var(id, "emissive", info.emissive)?;
        match index {
            Some(i) => self.made[i] = Some(id),
            None => self.default = Some(id),
        }
        self.out.push(crate::Material { id, info });
        Ok(id)
    }

    fn done(self) -> Vec<crate::Material> {
        self.out
    }
}

impl MaterialInfo {
    fn from_obj(m: &crate::obj::MeshMaterial) -> MaterialInfo {
        MaterialInfo {
            name: m.name.clone(),
            base_color: m.diffuse.extend(1.0),
            emissive: m.emission,
            metallic: 0.0,
            ..Default::default()
        }
    }
}

impl Default for MaterialInfo {
    /// glTF's default material: white, fully metallic and rough (as the
    /// specification says), no texture, no emission.
    fn default() -> Self {
        MaterialInfo {
            name: "default".into(),
            base_color: Vec4::ONE,
            base_color_texture: None::<Texture>,
            metallic: 1.0,
            roughness: 1.0,
            emissive: Vec3::ZERO,
        }
    }
}
