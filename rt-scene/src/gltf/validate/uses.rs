//! Each accessor's component and element type as the glTF specification
//! allows it where it is used ("Meshes" and "Animations" in the
//! specification): the `gltf` crate's readers assume these, reading a
//! forbidden type as garbage or not at all (`unreachable!`).

use crate::error::GltfError;
use crate::gltf::Reader;
use gltf::json;
use gltf::json::accessor::{ComponentType as C, Type as T};
use gltf::json::animation::Property;
use gltf::json::mesh::Semantic;
use gltf::json::validation::Checked::Valid;

/// The element types and component types a use allows.
struct Allowed {
    what: &'static str,
    types: &'static [T],
    components: &'static [C],
}

const FLOAT: &[C] = &[C::F32];
const FLOAT_UNORM: &[C] = &[C::F32, C::U8, C::U16];
const ANY_NORM: &[C] = &[C::F32, C::I8, C::U8, C::I16, C::U16];

fn attribute(semantic: &Semantic) -> Allowed {
    let (what, types, components): (&str, &[T], &[C]) = match semantic {
        Semantic::Positions => ("POSITION", &[T::Vec3], FLOAT),
        Semantic::Normals => ("NORMAL", &[T::Vec3], FLOAT),
        Semantic::Tangents => ("TANGENT", &[T::Vec4], FLOAT),
        Semantic::TexCoords(_) => ("TEXCOORD_n", &[T::Vec2], FLOAT_UNORM),
        Semantic::Colors(_) => ("COLOR_n", &[T::Vec3, T::Vec4], FLOAT_UNORM),
        Semantic::Joints(_) => ("JOINTS_n", &[T::Vec4], &[C::U8, C::U16]),
        Semantic::Weights(_) => ("WEIGHTS_n", &[T::Vec4], FLOAT_UNORM),
    };
    Allowed { what, types, components }
}

/// `accessor`, used at `object` as `allowed` says, has a type it allows.
fn check_use(r: &Reader, root: &json::Root, object: &str, index: usize, allowed: &Allowed) -> Result<(), GltfError> {
    let a = &root.accessors[index];
    // Both checked valid by `refs`.
    let (Valid(c), Valid(t)) = (&a.component_type, &a.type_) else { return Ok(()) };
    if !allowed.types.contains(t) || !allowed.components.contains(&c.0) {
        let names = |cs: &[C]| cs.iter().map(|c| format!("{c:?}")).collect::<Vec<_>>().join(", ");
        let types = allowed.types.iter().map(|t| format!("{t:?}")).collect::<Vec<_>>().join(" or ");
        return Err(r.error(
            object,
            format!(
                "accessors[{index}] is {t:?} of {:?}, but {} must be {types} of {}",
                c.0,
                allowed.what,
                names(allowed.components)
            ),
        ));
    }
    Ok(())
}

pub(super) fn check(r: &Reader, root: &json::Root) -> Result<(), GltfError> {
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let object = format!("meshes[{m}].primitives[{p}]");
            for (semantic, accessor) in &primitive.attributes {
                if let Valid(semantic) = semantic {
                    let at = format!("{object}.attributes.{}", semantic_name(semantic));
                    check_use(r, root, &at, accessor.value(), &attribute(semantic))?;
                }
            }
            if let Some(indices) = &primitive.indices {
                let allowed = Allowed { what: "indices", types: &[T::Scalar], components: &[C::U8, C::U16, C::U32] };
                check_use(r, root, &format!("{object}.indices"), indices.value(), &allowed)?;
            }
            for (t, target) in primitive.targets.iter().flatten().enumerate() {
                for (what, a) in
                    [("POSITION", &target.positions), ("NORMAL", &target.normals), ("TANGENT", &target.tangents)]
                {
                    if let Some(a) = a {
                        let allowed = Allowed { what, types: &[T::Vec3], components: FLOAT };
                        check_use(r, root, &format!("{object}.targets[{t}].{what}"), a.value(), &allowed)?;
                    }
                }
            }
        }
    }
    for (a, animation) in root.animations.iter().enumerate() {
        for (c, channel) in animation.channels.iter().enumerate() {
            let object = format!("animations[{a}].channels[{c}]");
            let sampler = &animation.samplers[channel.sampler.value()];
            let input = Allowed { what: "an animation's input", types: &[T::Scalar], components: FLOAT };
            check_use(r, root, &format!("{object} input"), sampler.input.value(), &input)?;
            let Valid(path) = &channel.target.path else { continue };
            let output = match path {
                Property::Translation => Allowed { what: "a translation", types: &[T::Vec3], components: FLOAT },
                Property::Scale => Allowed { what: "a scale", types: &[T::Vec3], components: FLOAT },
                Property::Rotation => Allowed { what: "a rotation", types: &[T::Vec4], components: ANY_NORM },
                Property::MorphTargetWeights => Allowed { what: "weights", types: &[T::Scalar], components: ANY_NORM },
            };
            check_use(r, root, &format!("{object} output"), sampler.output.value(), &output)?;
        }
    }
    for (i, skin) in root.skins.iter().enumerate() {
        if let Some(a) = &skin.inverse_bind_matrices {
            let allowed = Allowed { what: "inverseBindMatrices", types: &[T::Mat4], components: FLOAT };
            check_use(r, root, &format!("skins[{i}]"), a.value(), &allowed)?;
        }
    }
    Ok(())
}

/// The attribute's name as the file spells it.
fn semantic_name(s: &Semantic) -> String {
    match s {
        Semantic::Positions => "POSITION".into(),
        Semantic::Normals => "NORMAL".into(),
        Semantic::Tangents => "TANGENT".into(),
        Semantic::TexCoords(n) => format!("TEXCOORD_{n}"),
        Semantic::Colors(n) => format!("COLOR_{n}"),
        Semantic::Joints(n) => format!("JOINTS_{n}"),
        Semantic::Weights(n) => format!("WEIGHTS_{n}"),
    }
}
