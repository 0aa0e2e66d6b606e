//! The lane-wise variant of a generated program (`tests/fuzz_lanes.rs`):
//! the program with traces (`Stmt::Trace`) and early `return`s put into its
//! statement blocks (the body, branches, loop bodies, `match` arms), so
//! that, with each launch index's own inputs, some lanes of a block trace
//! and others do not, loops trace a lane-dependent number of times and
//! lanes leave the program early, each in a different place. The
//! interpreter runs it as the program it is: a trace changes only the
//! variant's own payload and ray buffer.

use super::*;

/// Program `id` of `seed` with traces and early returns.
pub fn lanes_variant(seed: u64, id: usize) -> Program {
    let mut p = program(seed, id);
    let mut r = Rng::new(program_seed(seed, id) ^ 0x1a2e_5a11_7ace_0001);
    let mut traces = 0;
    insert(&mut r, &mut p.body, &mut traces);
    p
}

/// Into `b` and the blocks of its statements: now and then a trace
/// (numbered from `traces`) and a `return` taken by some launch indices.
fn insert(r: &mut Rng, b: &mut Block, traces: &mut u32) {
    for s in b.stmts.iter_mut() {
        let s = match s {
            Stmt::Labelled(_, inner) => &mut **inner,
            s => s,
        };
        match s {
            Stmt::If(_, t, e) => {
                insert(r, t, traces);
                if let Some(e) = e {
                    insert(r, e, traces);
                }
            }
            Stmt::For { body, .. } | Stmt::Each { body, .. } | Stmt::While(_, body) | Stmt::Loop(body) => {
                insert(r, body, traces)
            }
            Stmt::Match(_, arms) => arms.iter_mut().for_each(|a| insert(r, &mut a.body, traces)),
            _ => {}
        }
    }
    if r.chance(45) {
        let at = r.below(b.stmts.len() as u64 + 1) as usize;
        b.stmts.insert(at, Stmt::Trace(*traces));
        *traces += 1;
    }
    if r.chance(10) {
        // `if launch_index().x % m == k { return; }`
        let m = r.pick(&[3u32, 5, 7, 11]);
        let k = r.below(m as u64) as u32;
        let lane = bin(BinOp::Rem, Expr::LaunchX, lit(LitV::U32(m), true));
        let c = bin(BinOp::Eq, lane, lit(LitV::U32(k), true));
        let at = r.below(b.stmts.len() as u64 + 1) as usize;
        b.stmts.insert(at, Stmt::If(c, Block { stmts: vec![Stmt::Return(None)], tail: None }, None));
    }
}
