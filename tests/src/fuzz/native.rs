//! A check of the interpreter itself: the printed programs compiled by
//! rustc (through the real `#[rt_program]` macros, as a Cargo project of
//! their own) and run natively with the same inputs, outputs compared with
//! the interpreter's. Too slow for every test run (one rustc build of
//! hundreds of programs), it backs the claim that [`super::interp`]
//! implements Rust's semantics; `cargo test -p rt-tests --test
//! fuzz_compiler -- --ignored` runs it. The build has overflow checks off
//! (release semantics: wrapping arithmetic, shifts modulo 32), as the
//! interpreter assumes.

use super::interp::{Stop, Word};
use super::{Prepared, gpu::LANES};
use std::fmt::Write;
use std::path::Path;

/// Writes the Cargo project running `programs` into `dir`.
pub fn write_project(dir: &Path, rt_std: &Path, programs: &[Prepared]) -> std::io::Result<()> {
    std::fs::create_dir_all(dir.join("src"))?;
    std::fs::write(
        dir.join("Cargo.toml"),
        format!(
            "[package]\nname = \"rt-fuzz-native\"\nversion = \"0.0.0\"\nedition = \"2024\"\npublish = false\n\n\
             [dependencies]\nrt-std = {{ path = {:?} }}\n\n\
             [profile.release]\nopt-level = 1\noverflow-checks = false\ndebug-assertions = false\n\n[workspace]\n",
            rt_std.display().to_string()
        ),
    )?;
    let mut main = String::from("#![allow(warnings)]\nuse rt_std::RtData;\nuse rt_std::prelude::*;\n\n");
    for p in programs {
        let _ = writeln!(main, "mod p{} {{\n{}\n}}\n", p.id, p.source);
    }
    main.push_str(
        "fn words<T: RtData>(v: &T, out: &mut String) {\n    let mut w = vec![0u32; T::LAYOUT.words as usize];\n    \
         v.write_words(&mut w);\n    for x in w {\n        out.push_str(&format!(\" {x:x}\"));\n    }\n}\n\n",
    );
    main.push_str("fn main() {\n");
    for p in programs {
        let _ = writeln!(main, "    run_p{}();", p.id);
    }
    main.push_str("}\n");
    for p in programs {
        let prog = &p.program;
        let _ = writeln!(main, "\nfn run_p{}() {{\n    use p{}::*;", p.id, p.id);
        main.push_str("    const INPUTS: &[&[u32]] = &[\n");
        for lane in &p.inputs {
            let mut w = Vec::new();
            for v in lane {
                v.words(&mut w);
            }
            let ws: Vec<String> = w
                .iter()
                .map(|w| match w {
                    Word::Int(b, _) => format!("{b:#x}"),
                    Word::Float(f, _) => format!("{:#x}", f.to_bits()),
                })
                .collect();
            let _ = writeln!(main, "        &[{}],", ws.join(", "));
        }
        main.push_str("    ];\n");
        let n = LANES * prog.slots;
        let _ = writeln!(
            main,
            "    for lane in 0..{LANES}u32 {{\n        let w = INPUTS[lane as usize];\n        let mut at = 0usize;"
        );
        let mut args = Vec::new();
        for (name, t) in &prog.inputs {
            let t = t.rust(prog);
            let _ = writeln!(
                main,
                "        let {name} = <{t} as RtData>::read_words(&w[at..]);\n        at += <{t} as RtData>::LAYOUT.words as usize;"
            );
            args.push(name.clone());
        }
        for (k, (_, t)) in prog.outputs.iter().enumerate() {
            let t = t.rust(prog);
            let _ = writeln!(
                main,
                "        let mut s{k}: Vec<{t}> = vec![Default::default(); {}];\n        let b{k} = unsafe {{ RwBuffer::from_raw_parts(s{k}.as_mut_ptr(), {n}) }};",
                n + 1
            );
            args.push(format!("b{k}"));
        }
        let _ = writeln!(
            main,
            "        let ctx = rt_std::cpu::ExecutionContext {{ launch_index: uvec2(lane, 0), launch_dim: uvec2({LANES}, 1), ..Default::default() }};\n        \
             rt_std::cpu::with_context(ctx, || {}({}));\n        let mut line = format!(\"P {} {{lane}}\");",
            prog.name,
            args.join(", "),
            p.id
        );
        for k in 0..prog.outputs.len() {
            let _ = writeln!(
                main,
                "        for e in &s{k}[(lane * {s}) as usize..((lane + 1) * {s}) as usize] {{\n            words(e, &mut line);\n        }}\n        line.push_str(\" |\");",
                s = prog.slots
            );
        }
        main.push_str("        println!(\"{line}\");\n    }\n}\n");
    }
    std::fs::write(dir.join("src/main.rs"), main)
}

/// Compares the native run's output (`P id lane words | words | ...` lines)
/// with the interpreter's; returns the differences found.
pub fn compare(programs: &[Prepared], output: &str) -> Vec<String> {
    let mut diffs = Vec::new();
    let mut seen = 0;
    for line in output.lines().filter(|l| l.starts_with("P ")) {
        let mut head = line.split(' ').skip(1);
        let id: usize = head.next().unwrap().parse().unwrap();
        let lane: usize = head.next().unwrap().parse().unwrap();
        let p = programs.iter().find(|p| p.id == id).expect("a program of the run");
        seen += 1;
        let bufs: Vec<Vec<u32>> = line
            .splitn(4, ' ')
            .nth(3)
            .unwrap_or("")
            .split('|')
            .map(|b| b.split_whitespace().map(|w| u32::from_str_radix(w, 16).unwrap()).collect())
            .filter(|b: &Vec<u32>| !b.is_empty() || p.program.slots == 0)
            .collect();
        let expected = match &p.expected[lane] {
            Ok(e) => e,
            // Nothing to compare; a NaN may well appear natively.
            Err(Stop::NonFinite(_) | Stop::Diverged(_)) => continue,
        };
        for (b, (want, got)) in expected.iter().zip(&bufs).enumerate() {
            for (k, (w, g)) in want.iter().zip(got).enumerate() {
                let ok = match *w {
                    Word::Int(_, true) => true,
                    Word::Int(x, false) => x == *g,
                    Word::Float(_, e) if !e.is_finite() => true,
                    Word::Float(f, e) => super::float_matches(f, e, f32::from_bits(*g)),
                };
                if !ok {
                    diffs.push(format!(
                        "program {id} launch index {lane}: {}[word {k}]: interpreter {w:?}, rustc {g:#x} ({:e})",
                        p.program.outputs[b].0,
                        f32::from_bits(*g)
                    ));
                }
            }
        }
    }
    let want: usize = programs.len() * LANES as usize;
    if seen != want {
        diffs.push(format!("the native run printed {seen} launch indices of {want}"));
    }
    diffs
}
