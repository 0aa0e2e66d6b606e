//! The hardware ray-query traversal: the megakernel's searches as
//! `rayQueryProceed` loops over acceleration structures the device builds
//! (a BLAS per geometry group, a TLAS per traced root), beside the compute
//! traversal ([`super::compute`]) and sharing everything else with it: the
//! scene's tables (geometry instances, materials, hit records), the heap,
//! the linker and the dispatch.
//!
//! Files: [`flatten`] (the graph as one level of instances per root, or why
//! it cannot be), [`accel`] (BLASes and TLASes on the device, rebuilt only
//! where something moved, and the kernel's side table), `search.wgsl` (the
//! loop) and [`wgsl`] (the per-kernel part: bindings, the slot switch).
//!
//! Which traversal a launch uses ([`Traversal`], [`plan`]): ray queries on
//! a GPU with `wgpu::Features::EXPERIMENTAL_RAY_QUERY` unless the scene
//! cannot be flattened (a selector, masks no 8-bit mask says) or the
//! context or `RT_TRAVERSAL` asks for the compute traversal; the compute
//! traversal otherwise, and on software adapters (lavapipe), whose ray
//! queries are slower than it unless asked for. The launch says once why a
//! scene fell back.

pub(crate) mod accel;
pub(crate) mod flatten;
pub(crate) mod wgsl;

use super::device::Gpu;
use crate::error::{ConfigError, Result};
use crate::scene::Scene;
use flatten::{Flat, Unsupported};

/// How the wgpu backend walks the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Traversal {
    /// Ray queries where a GPU has them and the scene allows, else the
    /// compute traversal (also on software adapters such as lavapipe,
    /// whose ray queries are slower); `RT_TRAVERSAL=compute|rayquery`
    /// overrides.
    #[default]
    Auto,
    /// The megakernel's own BVH walk in a compute shader (every adapter).
    Compute,
    /// Hardware ray queries (`wgpu::Features::EXPERIMENTAL_RAY_QUERY`): an
    /// error on an adapter without them.
    RayQuery,
}

impl Traversal {
    /// The traversal's name as `RT_TRAVERSAL` takes it (`auto`, `compute`,
    /// `rayquery`).
    pub fn name(self) -> &'static str {
        match self {
            Traversal::Auto => "auto",
            Traversal::Compute => "compute",
            Traversal::RayQuery => "rayquery",
        }
    }

    /// The traversal launches take on the default adapter with
    /// [`Traversal::Auto`], and why: `RT_TRAVERSAL` when set, else ray
    /// queries where the adapter has them. (A scene that cannot be
    /// flattened still takes the compute traversal, per launch: see
    /// [`crate::Context::traversal`].)
    pub fn choose() -> Result<(Traversal, String)> {
        if let Some(v) = crate::env_settings::setting("RT_TRAVERSAL") {
            return match Traversal::from_name(&v) {
                Some(Traversal::Auto) => Self::probe(),
                None => Err(ConfigError::Setting {
                    setting: "RT_TRAVERSAL",
                    value: v,
                    expected: "`auto`, `compute` or `rayquery`",
                }
                .into()),
                Some(t) => Ok((t, format!("RT_TRAVERSAL={v}"))),
            };
        }
        Self::probe()
    }

    /// What `Auto` takes on the default adapter, and why.
    fn probe() -> Result<(Traversal, String)> {
        Ok(match super::device::probe() {
            Some(info) if info.device_type == wgpu::DeviceType::Cpu => {
                let why = SOFTWARE.replace("{adapter}", &info.name);
                (
                    Traversal::Compute,
                    if super::device::probe_ray_queries() { why } else { format!("{} has no ray queries", info.name) },
                )
            }
            Some(info) if super::device::probe_ray_queries() => {
                (Traversal::RayQuery, format!("{} has ray queries", info.name))
            }
            Some(info) => (Traversal::Compute, format!("{} has no ray queries", info.name)),
            None => (Traversal::Compute, "no adapter".into()),
        })
    }

    /// Parses `auto`, `compute` or `rayquery`.
    pub fn from_name(name: &str) -> Option<Traversal> {
        match name {
            "auto" => Some(Traversal::Auto),
            "compute" => Some(Traversal::Compute),
            "rayquery" => Some(Traversal::RayQuery),
            _ => None,
        }
    }
}

/// What a launch's traversal is and why.
pub(crate) enum Plan {
    Compute(String),
    RayQuery(Flat),
}

/// Chooses the traversal for a launch over `scene` on `gpu`, asked for as
/// `asked` (`Auto` reads `RT_TRAVERSAL`).
pub(crate) fn plan(scene: &Scene, gpu: &Gpu, asked: Traversal) -> Result<Plan> {
    let asked = match (asked, crate::env_settings::setting("RT_TRAVERSAL")) {
        (Traversal::Auto, Some(v)) => Traversal::from_name(&v).ok_or_else(|| ConfigError::Setting {
            setting: "RT_TRAVERSAL",
            value: v.clone(),
            expected: "`auto`, `compute` or `rayquery`",
        })?,
        (asked, _) => asked,
    };
    if asked == Traversal::Compute {
        return Ok(Plan::Compute("asked for".into()));
    }
    if asked == Traversal::Auto && gpu.ray_query && gpu.is_cpu() {
        return Ok(Plan::Compute(SOFTWARE.replace("{adapter}", &gpu.describe())));
    }
    if !gpu.ray_query {
        let why = format!("{} has no ray queries (wgpu::Features::EXPERIMENTAL_RAY_QUERY)", gpu.describe());
        if asked == Traversal::RayQuery {
            return Err(ConfigError::Unsupported { asked: "the ray-query traversal", why }.into());
        }
        return Ok(Plan::Compute(why));
    }
    // The side table is one storage buffer more than the compute
    // traversal binds (an application's device may have no room for it).
    let storage = gpu.limits.max_storage_buffers_per_shader_stage as usize;
    if storage < 2 + gpu.scene_bindings + 1 {
        let why = format!(
            "the device binds {storage} storage buffers per stage; the ray-query traversal needs {}",
            2 + gpu.scene_bindings + 1
        );
        if asked == Traversal::RayQuery {
            return Err(ConfigError::Unsupported { asked: "the ray-query traversal", why }.into());
        }
        return Ok(Plan::Compute(why));
    }
    // A cycle in the graph is refused before flatten walks its paths (the
    // acceleration build, which refuses it too, runs after this choice).
    crate::scene::nodes_post_order(scene)?;
    match flatten::flatten(scene)? {
        Ok(flat) => Ok(Plan::RayQuery(flat)),
        Err(Unsupported::NoRoots) => Ok(Plan::Compute(Unsupported::NoRoots.to_string())),
        Err(why) => {
            let why = why.to_string();
            warn_once(&why);
            Ok(Plan::Compute(why))
        }
    }
}

/// Why `Auto` keeps the compute traversal on a software adapter that has
/// ray queries (lavapipe from Mesa 25): its ray queries are Mesa's own BVH
/// and traversal run by llvmpipe, slower than the megakernel's walk on
/// every bench scene (BENCHMARKS.md, "Ray queries").
const SOFTWARE: &str = "{adapter} is a software adapter, whose ray queries are slower than the compute traversal (BENCHMARKS.md); Traversal::RayQuery or RT_TRAVERSAL=rayquery uses them";

/// Says on stderr, once per reason, that a scene keeps the compute
/// traversal.
fn warn_once(why: &str) {
    static SAID: std::sync::Mutex<Vec<String>> = std::sync::Mutex::new(Vec::new());
    let mut said = SAID.lock().unwrap_or_else(|e| e.into_inner());
    if !said.iter().any(|s| s == why) {
        eprintln!("rt-runtime: this scene uses the compute traversal, not ray queries: {why}");
        said.push(why.to_string());
    }
}
