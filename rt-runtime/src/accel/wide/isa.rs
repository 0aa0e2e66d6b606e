//! Which instruction set the walk runs on: the best the CPU has (AVX2 with
//! FMA, else SSE4.1, else one lane at a time), or the one `RT_CPU_SIMD`
//! names (`avx2`, `sse4.1`, `scalar`), so the test suite can run each path
//! on one machine. Every path gives the same hits (see
//! `super::kernels`).

use super::WideBvh;
use super::kernels::{Hits, WalkRay, scalar::Scalar};
use super::walk::{Entry, stack_len, walk};
use std::mem::MaybeUninit;
use std::sync::OnceLock;

/// An instruction set the CPU backend's traversal is built for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Isa {
    /// 8-wide boxes, 4-wide triangles (x86_64 with AVX2 and FMA).
    Avx2,
    /// 4-wide boxes and triangles (x86_64 with SSE4.1).
    Sse41,
    /// One lane at a time (every target).
    Scalar,
}

/// The variable that forces an instruction set.
pub const ENV: &str = "RT_CPU_SIMD";

impl Isa {
    /// Every instruction set, widest first.
    pub const ALL: [Isa; 3] = [Isa::Avx2, Isa::Sse41, Isa::Scalar];

    /// The name `RT_CPU_SIMD` takes.
    pub fn name(self) -> &'static str {
        match self {
            Isa::Avx2 => "avx2",
            Isa::Sse41 => "sse4.1",
            Isa::Scalar => "scalar",
        }
    }

    /// Whether this CPU runs it.
    pub fn supported(self) -> bool {
        match self {
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma"),
            #[cfg(target_arch = "x86_64")]
            Isa::Sse41 => is_x86_feature_detected!("sse4.1"),
            #[cfg(not(target_arch = "x86_64"))]
            Isa::Avx2 | Isa::Sse41 => false,
            Isa::Scalar => true,
        }
    }

    /// The best this CPU runs.
    pub fn best() -> Isa {
        Isa::ALL.into_iter().find(|i| i.supported()).unwrap_or(Isa::Scalar)
    }

    /// What the CPU backend uses: `RT_CPU_SIMD`'s if set (and supported;
    /// else the best, with a warning on stderr), else the best. Read once.
    pub fn current() -> Isa {
        static CURRENT: OnceLock<Isa> = OnceLock::new();
        *CURRENT.get_or_init(|| {
            let Some(name) = crate::env_settings::setting(ENV) else { return Isa::best() };
            match Isa::ALL.into_iter().find(|i| i.name() == name.trim()) {
                Some(i) if i.supported() => i,
                Some(i) => {
                    eprintln!("{ENV}={name}: this CPU has no {}; using {}", i.name(), Isa::best().name());
                    Isa::best()
                }
                None => {
                    let names: Vec<&str> = Isa::ALL.iter().map(|i| i.name()).collect();
                    eprintln!("{ENV}={name}: not one of {}; using {}", names.join(", "), Isa::best().name());
                    Isa::best()
                }
            }
        })
    }
}

/// Walks `tree` on `isa` (see [`walk`]); `isa` must be supported.
#[inline(always)]
pub(crate) fn walk_on<F: FnMut(u32, Option<&Hits>) -> Option<f32>>(
    isa: Isa,
    tree: &WideBvh,
    ray: &WalkRay,
    tmax: f32,
    leaf: F,
) {
    const ON_STACK: usize = 7 * 48 + 1;
    let mut array = [const { MaybeUninit::<Entry>::uninit() }; ON_STACK];
    let mut heap = Vec::new();
    let stack: &mut [MaybeUninit<Entry>] = if stack_len(tree) <= ON_STACK {
        &mut array
    } else {
        heap.resize(stack_len(tree), MaybeUninit::uninit());
        &mut heap
    };
    match isa {
        // SAFETY: `isa` is supported (its caller's contract).
        #[cfg(target_arch = "x86_64")]
        Isa::Avx2 => unsafe { walk_avx2(tree, ray, tmax, stack, leaf) },
        #[cfg(target_arch = "x86_64")]
        Isa::Sse41 => unsafe { walk_sse41(tree, ray, tmax, stack, leaf) },
        _ => walk::<Scalar, F>(tree, ray, tmax, stack, leaf),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn walk_avx2<F: FnMut(u32, Option<&Hits>) -> Option<f32>>(
    tree: &WideBvh,
    ray: &WalkRay,
    tmax: f32,
    stack: &mut [MaybeUninit<Entry>],
    leaf: F,
) {
    walk::<super::kernels::x86::Avx2, F>(tree, ray, tmax, stack, leaf)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "sse4.1")]
unsafe fn walk_sse41<F: FnMut(u32, Option<&Hits>) -> Option<f32>>(
    tree: &WideBvh,
    ray: &WalkRay,
    tmax: f32,
    stack: &mut [MaybeUninit<Entry>],
    leaf: F,
) {
    walk::<super::kernels::x86::Sse41, F>(tree, ray, tmax, stack, leaf)
}
