//! How the CPU backend runs ray programs: lane-wise, a block of launch
//! indices per call where the program has a lane-wise form
//! (`rt_std::cpu::lanes`), or one launch index at a time (the scalar copy,
//! what a debugger steps through, and the default). `RT_CPU_EXEC=scalar|lanes`
//! chooses for every context that has not chosen
//! ([`crate::Context::set_cpu_execution`]).

use rt_std::program::{CpuLanes, ProgramDescriptor};
use std::sync::OnceLock;

/// How the CPU backend runs programs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CpuExecution {
    /// Lane-wise where the program has a lane-wise form, else scalar.
    Lanes,
    /// One launch index at a time, always (the default: the lane-wise form
    /// measures slower on the bunny today; BENCHMARKS.md).
    #[default]
    Scalar,
}

/// The variable that forces a mode.
pub const ENV: &str = "RT_CPU_EXEC";

impl CpuExecution {
    /// Every mode.
    pub const ALL: [CpuExecution; 2] = [CpuExecution::Lanes, CpuExecution::Scalar];

    /// The name `RT_CPU_EXEC` takes.
    pub fn name(self) -> &'static str {
        match self {
            CpuExecution::Lanes => "lanes",
            CpuExecution::Scalar => "scalar",
        }
    }

    /// `RT_CPU_EXEC`'s mode if set (a name it does not know: the default,
    /// with a warning on stderr), else the default. Read once.
    pub fn from_env() -> CpuExecution {
        static MODE: OnceLock<CpuExecution> = OnceLock::new();
        *MODE.get_or_init(|| {
            let Some(name) = crate::env_settings::setting(ENV) else { return CpuExecution::default() };
            match CpuExecution::ALL.into_iter().find(|m| m.name() == name) {
                Some(m) => m,
                None => {
                    let names: Vec<&str> = CpuExecution::ALL.iter().map(|m| m.name()).collect();
                    let default = CpuExecution::default().name();
                    eprintln!("{ENV}={name}: not one of {}; using {default}", names.join(", "));
                    CpuExecution::default()
                }
            }
        })
    }
}

/// How the CPU backend runs one program: lane-wise, or one launch index at
/// a time and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProgramExecution {
    /// The program's Rust name.
    pub program: &'static str,
    /// `None`: lane-wise; else why it runs one launch index at a time.
    pub scalar_because: Option<String>,
}

impl ProgramExecution {
    /// How `desc` runs under `mode`.
    pub fn of(desc: &ProgramDescriptor, mode: CpuExecution) -> ProgramExecution {
        let scalar_because = match (mode, desc.cpu_lanes) {
            (CpuExecution::Scalar, _) => {
                Some(format!("the context runs one launch index at a time (CpuExecution::Scalar; {ENV}=lanes)"))
            }
            (CpuExecution::Lanes, CpuLanes::Lanes(_)) => None,
            (CpuExecution::Lanes, CpuLanes::Scalar(why)) => Some(why.to_string()),
        };
        ProgramExecution { program: desc.name, scalar_because }
    }
}
