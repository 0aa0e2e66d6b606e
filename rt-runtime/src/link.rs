//! Linking: checks that the programs of a context fit together and resolves
//! every variable of every program use to a value, once per launch.
//!
//! Checks: each ray type has a miss program; the programs of a ray type agree
//! on the payload type, and every traced payload type is some ray type's;
//! intersection programs report the attribute type their hit programs take;
//! each variable is set in some scope of the program's lookup order
//! ([`crate::vars::lookup_order`]) with the declared type; callable
//! programs call each other in no cycle ([`callables`]).

pub mod callables;
pub(crate) mod instances;

use crate::buffer::SamplerShape;
use crate::error::{LinkError, Result, RtError, SceneError};
use crate::scene::{GeometryKind, NodeId, ProgramId};
use crate::scene::{Scene, Scope};
use crate::vars::{ScopeKind, VarValue, lookup_order};
use rt_std::program::{LayoutKind, ProgramDescriptor, SamplerKind, ScalarKind, TypeLayout, VariableKind};
use std::any::Any;
use std::sync::Arc;

/// Programs take at most this many variables (the CPU backend passes them
/// in a fixed-size array: no allocation per call).
pub const MAX_VARIABLES: usize = 32;

/// A program with its variables resolved for one scope record.
pub struct Call {
    pub desc: &'static ProgramDescriptor,
    pub vars: Vec<Arc<dyn Any + Send + Sync>>,
}

/// What the default exception program writes (OptiX's error colour; the
/// CPU backend's, not built for wasm32).
#[cfg(not(target_arch = "wasm32"))]
pub const EXCEPTION_COLOR: glam::Vec4 = glam::Vec4::new(1.0, 0.0, 1.0, 1.0);

/// The variable the default exception program paints (an entry point
/// without an exception program): the ray-generation program's first
/// `RwBuffer2d<Vec4>` variable, by index in its declaration order.
pub fn default_exception_output(ray_generation: &ProgramDescriptor) -> Option<usize> {
    ray_generation.variables.iter().position(
        |v| matches!(v.kind, VariableKind::Buffer { element, dimensions: 2, writable: true } if element.kind == VEC4),
    )
}

/// `Vec4`'s kind.
const VEC4: LayoutKind = LayoutKind::Vector { scalar: ScalarKind::F32, len: 4 };

/// The ids a program use is resolved against.
#[derive(Clone, Copy, Default)]
pub struct Record {
    pub instance: Option<crate::handles::GeometryInstanceId>,
    pub material: Option<crate::handles::MaterialId>,
    pub geometry: Option<crate::handles::GeometryId>,
    pub node: Option<NodeId>,
}

fn scope_name(s: Scope) -> String {
    match s {
        Scope::Context => "context".into(),
        Scope::Program(p) => format!("program {}", p.index()),
        Scope::Geometry(g) => format!("geometry {}", g.index()),
        Scope::GeometryInstance(g) => format!("geometry instance {}", g.index()),
        Scope::Material(m) => format!("material {}", m.index()),
        Scope::Node(n) => format!("node {}", n.index()),
    }
}

/// Finds and type-checks the values of program `p`'s variables used at
/// `record`, in declaration order.
pub fn resolve_values(scene: &Scene, p: ProgramId, record: Record) -> Result<Vec<&VarValue>> {
    let desc = scene.program(p)?.desc;
    if desc.variables.len() > MAX_VARIABLES {
        return Err(LinkError::TooManyVariables {
            program: desc.name,
            location: desc.location(),
            count: desc.variables.len(),
            max: MAX_VARIABLES,
        }
        .into());
    }
    let scopes: Vec<Scope> = lookup_order(desc.kind)
        .iter()
        .filter_map(|k| match k {
            ScopeKind::Program => Some(Scope::Program(p)),
            ScopeKind::Context => Some(Scope::Context),
            ScopeKind::GeometryInstance => record.instance.map(Scope::GeometryInstance),
            ScopeKind::Material => record.material.map(Scope::Material),
            ScopeKind::Geometry => record.geometry.map(Scope::Geometry),
            ScopeKind::Node => record.node.map(Scope::Node),
        })
        .collect();
    let mut values = Vec::with_capacity(desc.variables.len());
    for v in desc.variables {
        let mut found = None;
        for s in &scopes {
            if let Some(value) = scene.scope(*s)?.get(v.name) {
                found = Some((*s, value));
                break;
            }
        }
        let Some((scope, value)) = found else {
            return Err(LinkError::VariableNotFound {
                program: desc.name,
                location: desc.location(),
                kind: desc.kind,
                variable: v.name.to_string(),
                searched: scopes.iter().map(|s| scope_name(*s)).collect::<Vec<_>>().join(", "),
            }
            .into());
        };
        let mismatch = |found: String| {
            LinkError::VariableType {
                program: desc.name,
                location: desc.location(),
                variable: v.name.to_string(),
                declared: v.ty.rust.to_string(),
                scope: scope_name(scope),
                found,
            }
            .into()
        };
        let ok = match (value, v.kind) {
            (VarValue::Data { layout, words, .. }, VariableKind::Value) => {
                let ok = layout_compatible(layout, &v.ty);
                if ok {
                    let scope = scope_name(scope);
                    match v.ty.kind {
                        LayoutKind::Callable(Some(sig)) => check_callable_id(scene, desc, v, sig, &scope, words[0])?,
                        LayoutKind::BufferId { writable, element: Some(element) } => {
                            check_bindless_id(scene, desc, v, (element, writable), &scope, words[0])?
                        }
                        LayoutKind::SamplerId(Some(shape)) => {
                            check_sampler_id(scene, desc, v, shape, &scope, words[0])?
                        }
                        _ => {}
                    }
                }
                ok
            }
            (VarValue::Buffer(b), VariableKind::Buffer { element, dimensions, writable }) => {
                let rec =
                    scene.buffers.get(b.index() as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{b:?}")))?;
                layout_compatible(&rec.storage.layout(), &element)
                    && rec.dims == dimensions
                    && (!writable || rec.ty.writable_by_programs())
            }
            (VarValue::Sampler(s), VariableKind::Sampler | VariableKind::Sampler3d | VariableKind::SamplerCube) => {
                let rec = scene
                    .samplers
                    .get(s.index() as usize)
                    .ok_or_else(|| SceneError::InvalidHandle(format!("{s:?}")))?;
                let fits = match rec.shape {
                    SamplerShape::Flat => v.kind == VariableKind::Sampler,
                    SamplerShape::Volume(_) => v.kind == VariableKind::Sampler3d,
                    SamplerShape::Cube => v.kind == VariableKind::SamplerCube,
                };
                if !fits {
                    return Err(mismatch(format!("{} ({s:?})", rec.type_name())));
                }
                true
            }
            (VarValue::Object(n), VariableKind::Object) => {
                if n.index() as usize >= scene.nodes.len() {
                    return Err(SceneError::InvalidHandle(format!("{n:?}")).into());
                }
                true
            }
            _ => false,
        };
        if !ok {
            return Err(mismatch(value.type_name(
                &|b| scene.buffers.get(b.index() as usize).map(|r| r.type_name()).unwrap_or_else(|| format!("{b:?}")),
                &|s| scene.samplers.get(s.index() as usize).map_or_else(|| format!("{s:?}"), |r| r.type_name().into()),
            )));
        }
        values.push(value);
    }
    Ok(values)
}

/// Resolves the variables of program `p` used at `record` to the values the
/// CPU entry receives (handles for buffers, samplers and nodes).
pub fn resolve(scene: &Scene, p: ProgramId, record: Record) -> Result<Call> {
    let desc = scene.program(p)?.desc;
    let values = resolve_values(scene, p, record)?;
    let vars = values
        .into_iter()
        .zip(desc.variables)
        .map(|(value, v)| -> Arc<dyn Any + Send + Sync> {
            match (value, v.kind) {
                (VarValue::Data { value, .. }, _) => value.clone(),
                (VarValue::Buffer(b), VariableKind::Buffer { dimensions, writable, .. }) => {
                    let rec = &scene.buffers[b.index() as usize];
                    Arc::from(rec.storage.handle(dimensions, writable, [rec.width, rec.height, rec.depth]))
                }
                (VarValue::Sampler(s), VariableKind::Sampler3d) => {
                    Arc::new(scene.samplers[s.index() as usize].handle_3d())
                }
                (VarValue::Sampler(s), VariableKind::SamplerCube) => {
                    Arc::new(scene.samplers[s.index() as usize].handle_cube())
                }
                (VarValue::Sampler(s), _) => Arc::new(scene.samplers[s.index() as usize].handle()),
                (VarValue::Object(n), _) => Arc::new(n.object()),
                (VarValue::Buffer(_), _) => unreachable!("checked by resolve_values"),
            }
        })
        .collect();
    Ok(Call { desc, vars })
}

/// Payload and attribute agreement across the whole context.
pub fn check_types(scene: &Scene) -> Result<()> {
    let mut payload_of_ray_type: Vec<Option<(&'static ProgramDescriptor, TypeLayout)>> =
        vec![None; scene.ray_type_count() as usize];
    let mut note = |ray_type: u32, desc: &'static ProgramDescriptor| -> Result<()> {
        let Some(payload) = desc.payload else { return Ok(()) };
        let slot = &mut payload_of_ray_type[ray_type as usize];
        match slot {
            Some((other, layout)) if layout.rust != payload.rust => Err(LinkError::PayloadMismatch {
                ray_type,
                a: other.name,
                a_location: other.location(),
                a_type: layout.rust,
                b: desc.name,
                b_location: desc.location(),
                b_type: payload.rust,
            }
            .into()),
            Some(_) => Ok(()),
            None => {
                *slot = Some((desc, payload));
                Ok(())
            }
        }
    };
    for (r, m) in scene.miss.iter().enumerate() {
        if let Some(p) = m {
            note(r as u32, scene.program(*p)?.desc)?;
        }
    }
    for mat in &scene.materials {
        for (r, (ch, ah)) in mat.closest_hit.iter().zip(&mat.any_hit).enumerate() {
            for p in [ch, ah].into_iter().flatten() {
                note(r as u32, scene.program(*p)?.desc)?;
            }
        }
    }
    for prog in &scene.programs {
        for traced in prog.desc.traced_payloads {
            let known = payload_of_ray_type.iter().flatten().any(|(_, l)| l.rust == traced.rust);
            if !known {
                return Err(LinkError::TracedPayloadUnused {
                    program: prog.desc.name,
                    location: prog.desc.location(),
                    payload: traced.rust,
                }
                .into());
            }
        }
    }
    // Attributes: what an intersection program reports is what the hit
    // programs of its instances' materials take.
    for gi in &scene.instances {
        let geometry = &scene.geometries[gi.geometry.index() as usize];
        let GeometryKind::Custom { intersection, .. } = geometry.kind else { continue };
        let isect = scene.program(intersection)?.desc;
        for m in &gi.materials {
            let mat = &scene.materials[m.index() as usize];
            for p in mat.closest_hit.iter().chain(&mat.any_hit).flatten() {
                let hit = scene.program(*p)?.desc;
                if let (Some(taken), reported) = (hit.attributes, isect.attributes)
                    && reported.is_none_or(|r| r.rust != taken.rust)
                {
                    return Err(LinkError::AttributeMismatch {
                        intersection: isect.name,
                        intersection_location: isect.location(),
                        reported: reported.map(|r| r.rust).unwrap_or("no attributes"),
                        hit: hit.name,
                        hit_location: hit.location(),
                        taken: taken.rust,
                    }
                    .into());
                }
            }
        }
    }
    Ok(())
}

/// The variable references of a call, without allocating.
pub fn var_refs(call: &Call) -> [&(dyn Any + Send + Sync); MAX_VARIABLES] {
    let mut refs: [&(dyn Any + Send + Sync); MAX_VARIABLES] = [&(); MAX_VARIABLES];
    for (r, v) in refs.iter_mut().zip(&call.vars) {
        *r = &**v;
    }
    refs
}

/// The error for a value that the program's own binding
/// ([`ProgramDescriptor::cpu_bind`]) rejects: a Rust type other than the
/// declared one, though its name passed the link check.
pub fn bind_error(call: &Call, e: rt_std::cpu::VariableMismatch) -> RtError {
    let desc = call.desc;
    LinkError::VariableType {
        program: desc.name,
        location: desc.location(),
        variable: desc.variables.get(e.index).map_or_else(|| format!("#{}", e.index), |v| v.name.to_string()),
        declared: e.expected.to_string(),
        scope: "bound".to_string(),
        found: "a value of another Rust type".to_string(),
    }
    .into()
}

/// Whether a value laid out as `held` may be read as the declared type:
/// the same type (the same kind, and for a struct or enum the same name:
/// Rust's types are nominal), or an id for an id variable of the same
/// kind, whatever the host's layout knows of what it names (a
/// `Callable<F>` value's layout does not carry `F`): the id's target is
/// checked against the declaration by `check_callable_id`,
/// `check_bindless_id` and `check_sampler_id`, and at each access.
pub(crate) fn layout_compatible(held: &TypeLayout, declared: &TypeLayout) -> bool {
    match (held.kind, declared.kind) {
        (LayoutKind::Callable(_), LayoutKind::Callable(_)) | (LayoutKind::SamplerId(_), LayoutKind::SamplerId(_)) => {
            true
        }
        (LayoutKind::BufferId { writable: a, .. }, LayoutKind::BufferId { writable: b, .. }) => a == b,
        (a, b) => a == b && held.rust == declared.rust && held.words == declared.words,
    }
}

/// A `BindlessBuffer<T>` (`RwBindlessBuffer<T>`) variable's id against the
/// buffer it names: zero (none) or a buffer of elements `T` (one programs
/// may write, for a writable id).
fn check_bindless_id(
    scene: &Scene,
    desc: &'static ProgramDescriptor,
    v: &rt_std::program::VariableDescriptor,
    (element, writable): (&TypeLayout, bool),
    scope: &str,
    id: u32,
) -> Result<()> {
    let Some(named) = crate::handles::BufferId::from_bindless_id(id) else {
        return Ok(());
    };
    let error = |found: String| bindless_error(desc, v, scope, found);
    let Some(rec) = scene.buffers.get(named.index() as usize) else {
        return Err(error(format!("id {id}, which names no buffer of this context")));
    };
    let held = rec.storage.layout();
    if !layout_compatible(&held, element) {
        return Err(error(format!("the id of buffer {} of `{}` elements", named.index(), held.rust)));
    }
    if writable && !rec.ty.writable_by_programs() {
        return Err(error(format!(
            "the id of buffer {}, an {:?} buffer programs may not write (use a `BindlessBuffer<{}>`)",
            named.index(),
            rec.ty,
            element.rust
        )));
    }
    Ok(())
}

/// A bindless id variable `v` of `desc`, set in `scope`, that does not
/// name what it declares: `found` says what it names.
fn bindless_error(
    desc: &'static ProgramDescriptor,
    v: &rt_std::program::VariableDescriptor,
    scope: &str,
    found: String,
) -> crate::error::RtError {
    LinkError::BindlessVariable {
        program: desc.name,
        location: desc.location(),
        variable: v.name.to_string(),
        declared: v.ty.rust.to_string(),
        scope: scope.to_string(),
        found,
    }
    .into()
}

/// A `BindlessSampler<S>` variable's id against the sampler it names: zero
/// (none) or a sampler of shape `S`.
fn check_sampler_id(
    scene: &Scene,
    desc: &'static ProgramDescriptor,
    v: &rt_std::program::VariableDescriptor,
    shape: SamplerKind,
    scope: &str,
    id: u32,
) -> Result<()> {
    let Some(named) = crate::handles::SamplerId::from_bindless_id(id) else {
        return Ok(());
    };
    let error = |found: String| bindless_error(desc, v, scope, found);
    let Some(rec) = scene.samplers.get(named.index() as usize) else {
        return Err(error(format!("id {id}, which names no sampler of this context")));
    };
    let held = match rec.shape {
        SamplerShape::Flat => SamplerKind::Flat,
        SamplerShape::Volume(_) => SamplerKind::Volume,
        SamplerShape::Cube => SamplerKind::Cube,
    };
    if held != shape {
        return Err(error(format!("the id of sampler {}, a `{}`", named.index(), rec.type_name())));
    }
    Ok(())
}

/// A `Callable<F>` variable's id against the program it names: zero (none)
/// or a callable program of signature `F`.
fn check_callable_id(
    scene: &Scene,
    desc: &'static ProgramDescriptor,
    v: &rt_std::program::VariableDescriptor,
    declared: &rt_std::program::CallableSignature,
    scope: &str,
    id: u32,
) -> Result<()> {
    let Some(named) = ProgramId::from_callable_id(id) else {
        return Ok(());
    };
    let error = |found: String| {
        LinkError::CallableVariable {
            program: desc.name,
            location: desc.location(),
            variable: v.name.to_string(),
            declared: v.ty.rust.to_string(),
            scope: scope.to_string(),
            found,
        }
        .into()
    };
    let Some(target) = scene.programs.get(named.index() as usize).map(|r| r.desc) else {
        return Err(error(format!("id {id}, which names no program of this context")));
    };
    match target.callable {
        Some(c) if c.signature == *declared => Ok(()),
        Some(c) => Err(error(format!(
            "the id of `{}` ({}), a callable of signature `{}`",
            target.name,
            target.location(),
            c.signature.rust
        ))),
        None => Err(error(format!("the id of `{}` ({}), a {:?} program", target.name, target.location(), target.kind))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rt_std::RtData;
    use rt_std::program::LayoutKind;

    const fn named(rust: &'static str, kind: LayoutKind) -> TypeLayout {
        TypeLayout { kind, rust, wgsl: rust, words: 1, fields: &[] }
    }

    #[test]
    fn layouts_match_by_kind_and_name_and_ids_by_kind() {
        assert!(layout_compatible(&u32::LAYOUT, &u32::LAYOUT));
        assert!(!layout_compatible(&u32::LAYOUT, &i32::LAYOUT));
        assert!(!layout_compatible(&f32::LAYOUT, &named("f32", LayoutKind::Enum)));
        assert!(!layout_compatible(&named("A", LayoutKind::Struct), &named("B", LayoutKind::Struct)));
        // The host's id layouts know nothing of what they name.
        let declared_buffer =
            named("BindlessBuffer<u32>", LayoutKind::BufferId { writable: false, element: Some(&u32::LAYOUT) });
        assert!(layout_compatible(&rt_std::bindless::BINDLESS_LAYOUT, &declared_buffer));
        assert!(!layout_compatible(&rt_std::bindless::RW_BINDLESS_LAYOUT, &declared_buffer));
        let sampler = named("BindlessSampler<Sampler2d>", LayoutKind::SamplerId(Some(SamplerKind::Flat)));
        assert!(layout_compatible(&rt_std::bindless_sampler::BINDLESS_SAMPLER_LAYOUT, &sampler));
        assert!(!layout_compatible(&u32::LAYOUT, &sampler));
    }
}
