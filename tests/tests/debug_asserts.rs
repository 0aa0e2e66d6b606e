//! `debug_assert!` in ray programs: with debug assertions on (tests are
//! built so by default), a false condition raises `EXCEPTION_PANIC` where
//! Rust would panic and the program goes on, in a program and in a helper,
//! on every target alike; on the CPU backend the record names the
//! assertion's file and line. A true one raises nothing. Off (`cargo test
//! --release`), nothing is raised (the modules themselves:
//! `rt-macros/compiler/tests/debug_asserts.rs`).

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

/// The square root of a value asserted not negative.
#[rt_function]
pub fn root(a: f32) -> f32 {
    debug_assert!(a >= 0.0, "a root of a negative number");
    a.abs().sqrt()
}

/// Index 1 fails the program's assertion, index 2 the helper's; word `2 i`
/// is what the program computed (it goes on), word `2 i + 1` the exception
/// program's mark.
#[rt_program(ray_generation)]
pub fn asserting(#[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    debug_assert!(i != 1);
    let r = if i == 2 { root(-16.0) } else { root((i * i) as f32) };
    out[2 * i] = r as u32 + 10;
}

#[rt_program(exception)]
pub fn marked(#[var] mut out: RwBuffer<u32>) {
    out[2 * launch_index().x + 1] = exception_code();
}

#[test]
fn a_false_assertion_raises_the_panic_exception_where_assertions_are_on() {
    let on_here = cfg!(debug_assertions);
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let name = on.name();
        let mut ctx = on.context();
        let out = ctx.create_buffer::<u32>(BufferType::InputOutput, vec![0; 8]);
        ctx.set_var(Scope::Context, "out", out).unwrap();
        let rg = ctx.create_program(&asserting::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let ex = ctx.create_program(&marked::PROGRAM);
        ctx.set_exception_program(0, ex).unwrap();
        let report = ctx.launch_1d(0, 4).unwrap();
        let records: Vec<(u32, u32)> = report.exceptions.iter().map(|e| (e.launch_index.x, e.code)).collect();
        let words = ctx.read_buffer::<u32>(out).unwrap();
        if !on_here {
            assert_eq!(records, vec![], "{name}");
            assert_eq!(words, vec![10, 0, 11, 0, 14, 0, 13, 0], "{name}");
            continue;
        }
        assert_eq!(records, vec![(1, EXCEPTION_PANIC), (2, EXCEPTION_PANIC)], "{name}");
        assert_eq!(words, vec![10, 0, 11, EXCEPTION_PANIC, 14, EXCEPTION_PANIC, 13, 0], "{name}");
        if on == On::CPU {
            let lines: Vec<u32> = report.exceptions.iter().map(|e| e.location.expect("a place").line()).collect();
            assert_eq!(lines, vec![26, 16], "{name}: the program's assertion, then the helper's");
            assert_eq!(report.exceptions[0].location.unwrap().file(), file!(), "{name}");
        }
    }
}
