//! Lowering time per program: the macro's whole pass (syn AST → checked →
//! WGSL → naga validation) for every program of the tour's examples and of
//! this bench, read from the sources in the repository. Each program gets
//! every `rt_*` item of its crate as its dependencies, as the macro's
//! dependency chain would give it.

use crate::json::Json;
use rt_compiler::lower::{Entry, lower};
use rt_compiler::{Declared, Item};
use std::path::Path;
use std::time::{Duration, Instant};

/// The source files: the examples crate's modules and this bench.
fn sources() -> Result<Vec<(String, String)>, String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let dir = root.join("examples/src");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .collect();
    files.sort();
    files.push(root.join("bench/src/main.rs"));
    files
        .iter()
        .map(|p| {
            let name = p.strip_prefix(&root).unwrap_or(p).display().to_string();
            std::fs::read_to_string(p).map(|s| (name, s)).map_err(|e| format!("{}: {e}", p.display()))
        })
        .collect()
}

/// Lowers every program `reps` times; records the best time of each.
pub fn measure(reps: usize, out: &mut Json) {
    let sources = match sources() {
        Ok(s) => s,
        Err(e) => {
            eprintln!("lowering: {e}");
            out.set("error", e);
            return;
        }
    };
    // Dependencies per crate: the examples' items, or the bench's.
    let crate_of = |file: &str| usize::from(file.starts_with("bench/"));
    let mut programs = Vec::new();
    let mut items: [Vec<Item>; 2] = Default::default();
    for (name, text) in &sources {
        let file: syn::File = match syn::parse_str(text) {
            Ok(f) => f,
            Err(e) => {
                out.child("failed").set(name, e.to_string());
                continue;
            }
        };
        for it in &file.items {
            match rt_compiler::declared(it) {
                Some(Ok(Declared::Program(k, f))) => programs.push((name.clone(), k, f)),
                Some(Ok(Declared::Item(i))) => items[crate_of(name)].push(i),
                _ => {}
            }
        }
    }
    let mut times = Vec::new();
    for (file, kind, f) in &programs {
        let key = format!("{}::{}", file.trim_end_matches(".rs"), f.sig.ident);
        let items = &items[crate_of(file)];
        if let Err(e) = lower(Entry::Program(*kind, f), items) {
            out.child("failed").set(&key, format!("{e:?}").chars().take(200).collect::<String>());
            continue;
        }
        let best = (0..reps)
            .map(|_| {
                let t = Instant::now();
                std::hint::black_box(lower(Entry::Program(*kind, f), items).ok());
                t.elapsed()
            })
            .min()
            .unwrap_or_default();
        times.push(best);
        out.child("per_program_ms").set(&key, best.as_secs_f64() * 1e3);
    }
    let n = times.len();
    let total: Duration = times.iter().sum();
    let max = times.iter().max().copied().unwrap_or_default();
    out.set("programs", n);
    out.set("mean_ms", if n > 0 { total.as_secs_f64() * 1e3 / n as f64 } else { f64::NAN });
    out.set("max_ms", max.as_secs_f64() * 1e3);
    out.set("best_of", reps);
    eprintln!(
        "lowering: {n} programs of the examples and the bench, mean {:.2} ms, max {:.2} ms (best of {reps})",
        if n > 0 { total.as_secs_f64() * 1e3 / n as f64 } else { f64::NAN },
        max.as_secs_f64() * 1e3
    );
}
