//! The numbers a scene is built from are finite and in range: node
//! transforms, perspective cameras, punctual lights, material factors. (A
//! JSON number beyond f32's range, `1e39`, reads as infinity.)

use crate::error::GltfError;
use crate::gltf::Reader;
use gltf::json;

fn finite(r: &Reader, object: &str, field: &str, values: &[f32]) -> Result<(), GltfError> {
    match values.iter().find(|v| !v.is_finite()) {
        Some(v) => Err(r.error(object, format!("{field} has {v}, which is not finite"))),
        None => Ok(()),
    }
}

pub(super) fn check(r: &Reader, root: &json::Root) -> Result<(), GltfError> {
    for (i, node) in root.nodes.iter().enumerate() {
        let object = format!("nodes[{i}]");
        if let Some(m) = &node.matrix {
            finite(r, &object, "matrix", m)?;
        }
        if let Some(t) = &node.translation {
            finite(r, &object, "translation", t)?;
        }
        if let Some(s) = &node.scale {
            finite(r, &object, "scale", s)?;
        }
        if let Some(q) = &node.rotation {
            finite(r, &object, "rotation", &q.0)?;
            if q.0.iter().all(|&c| c == 0.0) {
                return Err(r.error(&object, "rotation is the zero quaternion, which is no rotation".into()));
            }
        }
    }
    for (i, camera) in root.cameras.iter().enumerate() {
        let Some(p) = &camera.perspective else { continue };
        let object = format!("cameras[{i}]");
        if !(p.yfov.is_finite() && p.yfov > 0.0 && p.yfov < std::f32::consts::PI) {
            return Err(r.error(&object, format!("perspective.yfov {} is outside (0, pi) radians", p.yfov)));
        }
        if let Some(aspect) = p.aspect_ratio
            && !(aspect.is_finite() && aspect > 0.0)
        {
            return Err(r.error(&object, format!("perspective.aspectRatio {aspect} is not a positive number")));
        }
        if !(p.znear.is_finite() && p.znear > 0.0) {
            return Err(r.error(&object, format!("perspective.znear {} is not a positive number", p.znear)));
        }
    }
    if let Some(ext) = root.extensions.as_ref().and_then(|e| e.khr_lights_punctual.as_ref()) {
        for (i, light) in ext.lights.iter().enumerate() {
            let object = format!("KHR_lights_punctual.lights[{i}]");
            finite(r, &object, "color", &light.color)?;
            finite(r, &object, "intensity", &[light.intensity])?;
            if let Some(range) = light.range
                && !(range.is_finite() && range > 0.0)
            {
                return Err(r.error(&object, format!("range {range} is not a positive number")));
            }
            if let Some(spot) = &light.spot {
                finite(r, &object, "spot", &[spot.inner_cone_angle, spot.outer_cone_angle])?;
            }
        }
    }
    for (i, m) in root.materials.iter().enumerate() {
        let object = format!("materials[{i}]");
        let pbr = &m.pbr_metallic_roughness;
        finite(r, &object, "pbrMetallicRoughness.baseColorFactor", &pbr.base_color_factor.0)?;
        finite(r, &object, "pbrMetallicRoughness.metallicFactor", &[pbr.metallic_factor.0])?;
        finite(r, &object, "pbrMetallicRoughness.roughnessFactor", &[pbr.roughness_factor.0])?;
        finite(r, &object, "emissiveFactor", &m.emissive_factor.0)?;
    }
    Ok(())
}
