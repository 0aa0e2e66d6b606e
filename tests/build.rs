//! Writes the compiler fuzzer's programs of the fixed seed as Rust source
//! (`$OUT_DIR/fuzz_lanes.rs`), which `tests/fuzz_lanes.rs` compiles through
//! the real `#[rt_program]` macro, so that the CPU backend runs each one
//! both one launch index at a time and lane-wise (see that test). The
//! generator is the fuzzer's own (`src/fuzz`: the AST, the generator and
//! the interpreter whose input values the generator draws), included by
//! path: a build script cannot use its own package's library.
//! `RT_FUZZ_LANES_PROGRAMS` sets how many programs (default 300).

#[allow(dead_code, unused_imports, clippy::all)]
#[path = "src/fuzz/ast/mod.rs"]
mod ast;
#[allow(dead_code, unused_imports, clippy::all)]
#[path = "src/fuzz/generate/mod.rs"]
mod generate;
#[allow(dead_code, unused_imports, clippy::all)]
#[path = "src/fuzz/interp/mod.rs"]
mod interp;

use ast::{Program, Scalar, Ty};
use std::fmt::Write;

/// The seed `tests/fuzz_compiler.rs` and `tests/fuzz_lanes.rs` run.
const SEED: u64 = 0x5eed;

fn main() {
    println!("cargo:rerun-if-changed=src/fuzz/ast");
    println!("cargo:rerun-if-changed=src/fuzz/generate");
    println!("cargo:rerun-if-changed=src/fuzz/interp");
    println!("cargo:rerun-if-env-changed=RT_FUZZ_LANES_PROGRAMS");
    let programs: usize = std::env::var("RT_FUZZ_LANES_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(300);
    // Generation recurses deeply.
    let out =
        std::thread::Builder::new().stack_size(256 << 20).spawn(move || corpus(programs)).unwrap().join().unwrap();
    let dir = std::env::var("OUT_DIR").unwrap();
    std::fs::write(std::path::Path::new(&dir).join("fuzz_lanes.rs"), out).unwrap();
}

/// The programs, each in a module `p<id>` with a function `setup_p<id>`
/// binding its buffers, and `PROGRAMS`, their table.
fn corpus(programs: usize) -> String {
    let mut out = format!("/// The seed the programs were generated with.\nconst SEED: u64 = {SEED:#x};\n");
    let mut table = String::new();
    for id in 0..programs {
        let p = generate::lanes_variant(SEED, id);
        let _ = writeln!(out, "\n#[allow(warnings, clippy::all)]\npub mod p{id} {{\n{}\n}}", p.lanes_source());
        out.push_str(&setup(id, &p));
        let _ = writeln!(
            table,
            "    Fuzzed {{ id: {id}, program: &p{id}::{}::PROGRAM, hit: &p{id}::fuzz_hit::PROGRAM, \
             miss: &p{id}::fuzz_miss::PROGRAM, setup: setup_p{id} }},",
            p.name
        );
    }
    let _ = writeln!(out, "\n/// Each program's id, descriptor and setup.\nconst PROGRAMS: &[Fuzzed] = &[\n{table}];");
    out
}

/// `setup_p<id>(ctx, inputs)`: the program's input buffers (one value per
/// launch index, from each index's words in `inputs`) and output buffers
/// (`slots` zeroed elements per launch index) bound as its variables; the
/// outputs' readers (their words).
fn setup(id: usize, p: &Program) -> String {
    let mut s = format!(
        "\n#[allow(unused_imports, clippy::all)]\nfn setup_p{id}(ctx: &mut Context, inputs: &[Vec<u32>]) -> Vec<Reader> {{\n    use p{id}::*;\n    use rt_std::prelude::*;\n    let mut readers: Vec<Reader> = Vec::new();\n"
    );
    let mut at = 0;
    for (n, t) in &p.inputs {
        let f = if *t == Ty::S(Scalar::Bool) { "input_bool".to_string() } else { format!("input::<{}>", t.rust(p)) };
        let _ = writeln!(s, "    {f}(ctx, \"fuzz_in_{n}\", inputs, {at});");
        at += p.words(t) as usize;
    }
    for (n, t) in &p.outputs {
        let _ = writeln!(s, "    readers.push(output::<{}>(ctx, \"{n}\", {}));", t.rust(p), p.slots);
    }
    s.push_str("    readers.push(output::<u32>(ctx, \"fuzz_rays\", 1));\n    readers\n}\n");
    s
}
