//! Every index into another of the document's arrays is in range, and
//! every enumerated value (component types, modes, paths, filters) is one
//! the specification names.

use super::{in_range, valid};
use crate::error::GltfError;
use crate::gltf::Reader;
use gltf::json;

pub(super) fn check(r: &Reader, root: &json::Root) -> Result<(), GltfError> {
    let n_accessors = root.accessors.len();
    if let Some(scene) = &root.scene {
        in_range(r, "scene", "it", scene, root.scenes.len(), "scenes")?;
    }
    for (i, view) in root.buffer_views.iter().enumerate() {
        let object = format!("bufferViews[{i}]");
        in_range(r, &object, "buffer", &view.buffer, root.buffers.len(), "buffers")?;
        if let Some(target) = &view.target {
            valid(r, &object, "target", target)?;
        }
    }
    for (i, a) in root.accessors.iter().enumerate() {
        let object = format!("accessors[{i}]");
        if let Some(view) = &a.buffer_view {
            in_range(r, &object, "bufferView", view, root.buffer_views.len(), "bufferViews")?;
        }
        valid(r, &object, "componentType", &a.component_type)?;
        valid(r, &object, "type", &a.type_)?;
        if let Some(sparse) = &a.sparse {
            let n = root.buffer_views.len();
            in_range(r, &object, "sparse.indices.bufferView", &sparse.indices.buffer_view, n, "bufferViews")?;
            valid(r, &object, "sparse.indices.componentType", &sparse.indices.component_type)?;
            in_range(r, &object, "sparse.values.bufferView", &sparse.values.buffer_view, n, "bufferViews")?;
        }
    }
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let object = format!("meshes[{m}].primitives[{p}]");
            valid(r, &object, "mode", &primitive.mode)?;
            for (semantic, accessor) in &primitive.attributes {
                let semantic = valid(r, &object, "an attribute's name", semantic)?;
                in_range(r, &object, &format!("attributes.{semantic:?}"), accessor, n_accessors, "accessors")?;
            }
            if let Some(indices) = &primitive.indices {
                in_range(r, &object, "indices", indices, n_accessors, "accessors")?;
            }
            if let Some(material) = &primitive.material {
                in_range(r, &object, "material", material, root.materials.len(), "materials")?;
            }
            for (t, target) in primitive.targets.iter().flatten().enumerate() {
                for (what, a) in
                    [("POSITION", &target.positions), ("NORMAL", &target.normals), ("TANGENT", &target.tangents)]
                {
                    if let Some(a) = a {
                        in_range(r, &object, &format!("targets[{t}].{what}"), a, n_accessors, "accessors")?;
                    }
                }
            }
        }
    }
    check_nodes(r, root)?;
    check_materials(r, root)?;
    check_animations(r, root)
}

fn check_nodes(r: &Reader, root: &json::Root) -> Result<(), GltfError> {
    let n_nodes = root.nodes.len();
    for (s, scene) in root.scenes.iter().enumerate() {
        for node in &scene.nodes {
            in_range(r, &format!("scenes[{s}]"), "nodes", node, n_nodes, "nodes")?;
        }
    }
    let lights = root.extensions.as_ref().and_then(|e| e.khr_lights_punctual.as_ref()).map_or(0, |l| l.lights.len());
    for (i, node) in root.nodes.iter().enumerate() {
        let object = format!("nodes[{i}]");
        for child in node.children.iter().flatten() {
            in_range(r, &object, "children", child, n_nodes, "nodes")?;
        }
        if let Some(mesh) = &node.mesh {
            in_range(r, &object, "mesh", mesh, root.meshes.len(), "meshes")?;
        }
        if let Some(camera) = &node.camera {
            in_range(r, &object, "camera", camera, root.cameras.len(), "cameras")?;
        }
        if let Some(skin) = &node.skin {
            in_range(r, &object, "skin", skin, root.skins.len(), "skins")?;
        }
        if let Some(light) = node.extensions.as_ref().and_then(|e| e.khr_lights_punctual.as_ref()) {
            in_range(r, &object, "KHR_lights_punctual.light", &light.light, lights, "KHR_lights_punctual lights")?;
        }
    }
    for (i, skin) in root.skins.iter().enumerate() {
        let object = format!("skins[{i}]");
        for joint in &skin.joints {
            in_range(r, &object, "joints", joint, n_nodes, "nodes")?;
        }
        if let Some(skeleton) = &skin.skeleton {
            in_range(r, &object, "skeleton", skeleton, n_nodes, "nodes")?;
        }
        if let Some(a) = &skin.inverse_bind_matrices {
            in_range(r, &object, "inverseBindMatrices", a, root.accessors.len(), "accessors")?;
        }
    }
    for (i, camera) in root.cameras.iter().enumerate() {
        let object = format!("cameras[{i}]");
        let present = match valid(r, &object, "type", &camera.type_)? {
            json::camera::Type::Perspective => camera.perspective.is_some(),
            json::camera::Type::Orthographic => camera.orthographic.is_some(),
        };
        if !present {
            return Err(r.error(&object, "its type's parameters (perspective or orthographic) are missing".into()));
        }
    }
    if let Some(ext) = root.extensions.as_ref().and_then(|e| e.khr_lights_punctual.as_ref()) {
        for (i, light) in ext.lights.iter().enumerate() {
            let object = format!("KHR_lights_punctual.lights[{i}]");
            let kind = valid(r, &object, "type", &light.type_)?;
            if *kind == json::extensions::scene::khr_lights_punctual::Type::Spot && light.spot.is_none() {
                return Err(r.error(&object, "a spot light without its `spot` parameters".into()));
            }
        }
    }
    Ok(())
}

fn check_materials(r: &Reader, root: &json::Root) -> Result<(), GltfError> {
    let n_textures = root.textures.len();
    for (i, m) in root.materials.iter().enumerate() {
        let object = format!("materials[{i}]");
        valid(r, &object, "alphaMode", &m.alpha_mode)?;
        let pbr = &m.pbr_metallic_roughness;
        let infos = [
            ("baseColorTexture", pbr.base_color_texture.as_ref().map(|t| &t.index)),
            ("metallicRoughnessTexture", pbr.metallic_roughness_texture.as_ref().map(|t| &t.index)),
            ("emissiveTexture", m.emissive_texture.as_ref().map(|t| &t.index)),
            ("normalTexture", m.normal_texture.as_ref().map(|t| &t.index)),
            ("occlusionTexture", m.occlusion_texture.as_ref().map(|t| &t.index)),
        ];
        for (what, index) in infos {
            if let Some(index) = index {
                in_range(r, &object, what, index, n_textures, "textures")?;
            }
        }
    }
    for (i, t) in root.textures.iter().enumerate() {
        let object = format!("textures[{i}]");
        in_range(r, &object, "source", &t.source, root.images.len(), "images")?;
        if let Some(sampler) = &t.sampler {
            in_range(r, &object, "sampler", sampler, root.samplers.len(), "samplers")?;
        }
    }
    for (i, s) in root.samplers.iter().enumerate() {
        let object = format!("samplers[{i}]");
        valid(r, &object, "wrapS", &s.wrap_s)?;
        valid(r, &object, "wrapT", &s.wrap_t)?;
        if let Some(f) = &s.mag_filter {
            valid(r, &object, "magFilter", f)?;
        }
        if let Some(f) = &s.min_filter {
            valid(r, &object, "minFilter", f)?;
        }
    }
    for (i, image) in root.images.iter().enumerate() {
        let object = format!("images[{i}]");
        match (&image.uri, &image.buffer_view) {
            (Some(_), None) => {}
            (None, Some(view)) => {
                in_range(r, &object, "bufferView", view, root.buffer_views.len(), "bufferViews")?;
                if image.mime_type.is_none() {
                    return Err(r.error(&object, "an image in a bufferView needs a mimeType".into()));
                }
            }
            _ => return Err(r.error(&object, "an image needs exactly one of uri and bufferView".into())),
        }
    }
    Ok(())
}

fn check_animations(r: &Reader, root: &json::Root) -> Result<(), GltfError> {
    for (a, animation) in root.animations.iter().enumerate() {
        for (s, sampler) in animation.samplers.iter().enumerate() {
            let object = format!("animations[{a}].samplers[{s}]");
            in_range(r, &object, "input", &sampler.input, root.accessors.len(), "accessors")?;
            in_range(r, &object, "output", &sampler.output, root.accessors.len(), "accessors")?;
            valid(r, &object, "interpolation", &sampler.interpolation)?;
        }
        for (c, channel) in animation.channels.iter().enumerate() {
            let object = format!("animations[{a}].channels[{c}]");
            let samplers = format!("animations[{a}].samplers");
            in_range(r, &object, "sampler", &channel.sampler, animation.samplers.len(), &samplers)?;
            in_range(r, &object, "target.node", &channel.target.node, root.nodes.len(), "nodes")?;
            valid(r, &object, "target.path", &channel.target.path)?;
        }
    }
    Ok(())
}
