//! Lowering time per program for the snapshot corpus (the seed's programs and
//! more), against a baseline measured in the same run: naga alone parsing and
//! validating the same WGSL. The ratio is how much the whole macro pass costs
//! over naga's share of it.
//!
//! `cargo bench -p rt-compiler --bench lowering` (add `-- --quick` for fewer
//! repetitions).

use rt_compiler::lower::{Entry, lower};
use rt_compiler::{Declared, Item};
use std::time::{Duration, Instant};

fn best_of(n: usize, mut f: impl FnMut()) -> Duration {
    (0..n)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed()
        })
        .min()
        .unwrap()
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let reps = if quick { 5 } else { 30 };
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/snapshots/in");
    let mut files: Vec<_> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    let mut programs = Vec::new();
    let mut items: Vec<Item> = Vec::new();
    for f in &files {
        let file: syn::File = syn::parse_str(&std::fs::read_to_string(f).unwrap()).unwrap();
        for it in &file.items {
            match rt_compiler::declared(it) {
                Some(Ok(Declared::Program(k, func))) => programs.push((k, func)),
                Some(Ok(Declared::Item(i))) => items.push(i),
                _ => {}
            }
        }
    }
    println!("{:<28} {:>12} {:>12} {:>8}", "program", "lower (ms)", "naga (ms)", "ratio");
    let (mut total_lower, mut total_naga) = (Duration::ZERO, Duration::ZERO);
    for (kind, f) in &programs {
        let wgsl = lower(Entry::Program(*kind, f), &items).expect("corpus lowers").wgsl;
        let t_lower = best_of(reps, || {
            std::hint::black_box(lower(Entry::Program(*kind, f), &items).unwrap());
        });
        let t_naga = best_of(reps, || {
            let m = naga::front::wgsl::parse_str(&wgsl).unwrap();
            naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::default())
                .validate(&m)
                .unwrap();
        });
        total_lower += t_lower;
        total_naga += t_naga;
        println!(
            "{:<28} {:>12.3} {:>12.3} {:>8.2}",
            f.sig.ident.to_string(),
            t_lower.as_secs_f64() * 1e3,
            t_naga.as_secs_f64() * 1e3,
            t_lower.as_secs_f64() / t_naga.as_secs_f64()
        );
    }
    let n = programs.len() as f64;
    println!(
        "mean over {} programs: lower {:.3} ms, naga alone {:.3} ms, ratio {:.2} (goal: lower < 10 ms)",
        programs.len(),
        total_lower.as_secs_f64() * 1e3 / n,
        total_naga.as_secs_f64() * 1e3 / n,
        total_lower.as_secs_f64() / total_naga.as_secs_f64()
    );
}
