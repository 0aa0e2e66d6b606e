//! Programs and where they run: creating programs from descriptors, entry
//! points' ray generation and exception programs, ray types' miss
//! programs, and callable programs' ids.

use super::Context;
use crate::error::{LinkError, Result};
use crate::scene::*;
use crate::vars::VarScope;
use rt_std::program::{ProgramDescriptor, ProgramKind};

impl Context {
    /// How the CPU backend runs programs: lane-wise where a program has a
    /// lane-wise form, or one launch index at a time (the default, and what
    /// a debugger steps through). Overrides `RT_CPU_EXEC` for this context.
    pub fn set_cpu_execution(&mut self, mode: crate::CpuExecution) {
        self.settings.cpu_execution = mode;
    }

    /// How the CPU backend runs each program created in this context, in
    /// creation order: lane-wise, or one launch index at a time and why
    /// (the construct its lane-wise lowering does not take, the program's
    /// kind, or the setting). Only ray generation programs run lane-wise;
    /// the programs their traces reach run one launch index at a time.
    pub fn cpu_execution(&self) -> Vec<crate::ProgramExecution> {
        let mode = self.settings.cpu_execution;
        self.scene.programs.iter().map(|p| crate::ProgramExecution::of(p.desc, mode)).collect()
    }

    /// Creates a program from a descriptor (`my_program::PROGRAM`).
    pub fn create_program(&mut self, desc: &'static ProgramDescriptor) -> ProgramId {
        self.scene.structure_version += 1;
        self.scene.programs.push(ProgramRec { desc, vars: VarScope::default() });
        ProgramId(self.scene.programs.len() as u32 - 1)
    }

    /// The id programs call callable program `p` through, as a
    /// [`Callable<F>`](rt_std::Callable) of the signature `F` the program
    /// was declared with (`fn(Vec3, Vec3) -> Vec3`): set it as a variable,
    /// or store it in a buffer, payload or struct. Errors if `p` is not a
    /// callable program or its signature is not `F`, naming the program.
    #[doc(alias = "rtProgramGetId")]
    pub fn callable_id<F: 'static>(&self, p: ProgramId) -> Result<rt_std::Callable<F>> {
        let desc = self.scene.program(p)?.desc;
        let Some(callable) = desc.callable else {
            return Err(LinkError::WrongProgramKind {
                program: desc.name,
                location: desc.location(),
                found: desc.kind,
                expected: ProgramKind::Callable,
                slot: "a callable id".into(),
            }
            .into());
        };
        if !callable.cpu.is::<F>() {
            return Err(LinkError::CallableSignature {
                program: desc.name,
                location: desc.location(),
                signature: callable.signature.rust,
                asked: short_type_name(std::any::type_name::<F>()),
            }
            .into());
        }
        Ok(rt_std::Callable::from_id(p.callable_id()))
    }

    pub(super) fn expect_kind(&self, p: ProgramId, expected: ProgramKind, slot: String) -> Result<()> {
        let desc = self.scene.program(p)?.desc;
        if desc.kind != expected {
            return Err(LinkError::WrongProgramKind {
                program: desc.name,
                location: desc.location(),
                found: desc.kind,
                expected,
                slot,
            }
            .into());
        }
        Ok(())
    }

    fn entry_mut(&mut self, entry: u32) -> Result<&mut EntryPoint> {
        let count = self.scene.entry_points.len() as u32;
        self.scene.entry_points.get_mut(entry as usize).ok_or(LinkError::NoSuchEntryPoint { entry, count }.into())
    }

    pub(super) fn check_ray_type(&self, ray_type: u32) -> Result<()> {
        if ray_type >= self.ray_type_count() {
            return Err(LinkError::NoSuchRayType { ray_type, count: self.ray_type_count() }.into());
        }
        Ok(())
    }

    /// Sets entry point `entry`'s ray-generation program: the program a
    /// launch of `entry` runs at every launch index.
    pub fn set_ray_generation_program(&mut self, entry: u32, p: ProgramId) -> Result<()> {
        self.scene.structure_version += 1;
        self.expect_kind(p, ProgramKind::RayGeneration, format!("entry point {entry}'s ray generation"))?;
        self.entry_mut(entry)?.ray_generation = Some(p);
        Ok(())
    }

    /// Sets entry point `entry`'s exception program: it runs at a launch
    /// index after the index's first exception, with the code in
    /// `exception_code()`. Every exception is also recorded in
    /// [`crate::LaunchReport::exceptions`], with or without an exception program.
    ///
    /// Without one, the default exception program runs (both backends): if
    /// the ray-generation program declares a `RwBuffer2d<Vec4>` variable
    /// (the first one, when it declares several), magenta `(1, 0, 1, 1)` is
    /// written into it at the launch index (skipped if the index is outside
    /// the buffer), so failing pixels stand out in the image.
    pub fn set_exception_program(&mut self, entry: u32, p: ProgramId) -> Result<()> {
        self.scene.structure_version += 1;
        self.expect_kind(p, ProgramKind::Exception, format!("entry point {entry}'s exception"))?;
        self.entry_mut(entry)?.exception = Some(p);
        Ok(())
    }

    /// Sets `ray_type`'s miss program: it runs for a ray of that type that
    /// hits nothing.
    pub fn set_miss_program(&mut self, ray_type: u32, p: ProgramId) -> Result<()> {
        self.scene.structure_version += 1;
        self.check_ray_type(ray_type)?;
        self.expect_kind(p, ProgramKind::Miss, format!("ray type {ray_type}'s miss"))?;
        self.scene.miss[ray_type as usize] = Some(p);
        Ok(())
    }
}

/// `fn(glam::f32::vec3::Vec3) -> glam::f32::vec3::Vec3` as
/// `fn(Vec3) -> Vec3`: every path cut to its last segment.
fn short_type_name(full: &str) -> String {
    let mut out = String::new();
    let mut word = String::new();
    for c in full.chars().chain(std::iter::once(' ')) {
        if c.is_alphanumeric() || c == '_' || c == ':' {
            word.push(c);
        } else {
            out.push_str(word.rsplit("::").next().unwrap_or(&word));
            word.clear();
            out.push(c);
        }
    }
    out.trim_end().to_string()
}
