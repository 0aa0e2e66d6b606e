//! Where a test runs: a backend and, on wgpu, a traversal ([`On`]). Suites
//! run each test on the CPU backend, the compute traversal and the
//! ray-query traversal; the last needs an adapter with ray queries
//! (lavapipe from Mesa 25, which `scripts/test.sh` installs): without one
//! its tests pass with a note, unless `RT_REQUIRE_RAY_QUERY=1` (set by
//! `scripts/test.sh`), when they fail.

use rt_runtime::{Backend, Context, Traversal};

/// A backend and the wgpu backend's traversal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct On {
    pub backend: Backend,
    pub traversal: Traversal,
}

impl On {
    pub const CPU: On = On { backend: Backend::Cpu, traversal: Traversal::Auto };
    pub const COMPUTE: On = On { backend: Backend::Wgpu, traversal: Traversal::Compute };
    pub const RAY_QUERY: On = On { backend: Backend::Wgpu, traversal: Traversal::RayQuery };
    /// Every target, for tests that compare them.
    pub const ALL: [On; 3] = [On::CPU, On::COMPUTE, On::RAY_QUERY];

    /// Makes `ctx` launch here.
    pub fn apply(self, ctx: &mut Context) {
        ctx.set_backend(self.backend);
        ctx.set_traversal(self.traversal);
    }

    /// A context that launches here.
    pub fn context(self) -> Context {
        let mut ctx = Context::new();
        self.apply(&mut ctx);
        ctx
    }

    /// Whether this target runs on this machine: ray queries need an
    /// adapter with them. Without one: false, with a note on stderr; a
    /// panic when `RT_REQUIRE_RAY_QUERY=1`.
    pub fn available(self) -> bool {
        if self.traversal != Traversal::RayQuery {
            return true;
        }
        static HAS: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
        let has = *HAS.get_or_init(rt_runtime::backend::wgpu::probe_ray_queries);
        if !has {
            let adapter = rt_runtime::backend::wgpu::probe().map_or("no adapter".to_string(), |i| i.name);
            assert!(
                std::env::var("RT_REQUIRE_RAY_QUERY").as_deref() != Ok("1"),
                "RT_REQUIRE_RAY_QUERY=1 but the adapter ({adapter}) has no ray queries"
            );
            eprintln!(
                "skipped: the adapter ({adapter}) has no ray queries (install Mesa 25's lavapipe: scripts/test.sh)"
            );
        }
        has
    }

    pub fn name(self) -> &'static str {
        match (self.backend, self.traversal) {
            (Backend::Cpu, _) => "cpu",
            (_, Traversal::RayQuery) => "rayquery",
            _ => "compute",
        }
    }
}

impl PartialEq<Backend> for On {
    fn eq(&self, other: &Backend) -> bool {
        self.backend == *other
    }
}

/// A backend as a target: wgpu with the compute traversal.
impl From<Backend> for On {
    fn from(backend: Backend) -> On {
        match backend {
            Backend::Wgpu => On::COMPUTE,
            _ => On::CPU,
        }
    }
}
