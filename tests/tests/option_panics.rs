//! `unwrap` and `expect` of an `Option` in ray programs: a `Some` gives its
//! value; a `None` raises `EXCEPTION_PANIC` where Rust would panic, and the
//! program goes on with the zero value, on every target alike. On the CPU
//! backend the record names the file and line of the call.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

/// The value at `k`, if `k` is even.
#[rt_function]
pub fn even(k: u32) -> Option<Vec2> {
    if k % 2 == 0 { Some(Vec2::new(k as f32, 1.5)) } else { None }
}

/// Index 0 unwraps a `Some`, 1 unwraps a `None` in a helper's result, 2
/// expects a `None`, 3 expects a `Some`. Word `2 i` is what the program
/// saw (and that it went on), word `2 i + 1` the exception program's mark.
#[rt_program(ray_generation)]
pub fn unwraps(#[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    let seen = match i {
        0 => even(4).unwrap().x as u32,
        1 => even(3).unwrap().y as u32 + 70,
        2 => {
            let o: Option<u32> = None;
            o.expect("an id") + 80
        }
        _ => Some(i * 10).expect("set"),
    };
    out[2 * i] = seen;
}

#[rt_program(exception)]
pub fn marked(#[var] mut out: RwBuffer<u32>) {
    out[2 * launch_index().x + 1] = exception_code();
}

#[test]
fn a_none_raises_the_panic_exception_and_the_program_goes_on_with_zero() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let name = on.name();
        let mut ctx = on.context();
        let out = ctx.create_buffer::<u32>(BufferType::InputOutput, vec![0; 8]);
        ctx.set_var(Scope::Context, "out", out).unwrap();
        let rg = ctx.create_program(&unwraps::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let ex = ctx.create_program(&marked::PROGRAM);
        ctx.set_exception_program(0, ex).unwrap();
        let report = ctx.launch_1d(0, 4).unwrap();
        let records: Vec<(u32, u32)> = report.exceptions.iter().map(|e| (e.launch_index.x, e.code)).collect();
        assert_eq!(records, vec![(1, EXCEPTION_PANIC), (2, EXCEPTION_PANIC)], "{name}");
        let words = ctx.read_buffer::<u32>(out).unwrap();
        assert_eq!(words, vec![4, 0, 70, EXCEPTION_PANIC, 80, EXCEPTION_PANIC, 30, 0], "{name}");
        if on == On::CPU {
            let at = report.exceptions[0].location.expect("the CPU backend records where");
            assert_eq!(at.file(), file!(), "{name}");
            assert_eq!(at.line(), 24, "{name}: the `unwrap` of index 1");
        }
    }
}
