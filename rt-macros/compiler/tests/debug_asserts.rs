//! `debug_assert!` through the compiler alone: with debug assertions on the
//! module raises `EXCEPTION_PANIC` where the condition is false, off it has
//! no trace of the assertion; the CPU copy calls rt-std's assertion, which
//! asks the declaring crate's `cfg!(debug_assertions)`; and the refusals.

use rt_compiler::lower::{Entry, lower, lower_without_debug_assertions};

const ITEMS: &str = "
    #[rt_function] pub fn checked(a: f32) -> f32 { debug_assert!(a >= 0.0); a.sqrt() }";

fn program(body: &str) -> (syn::ItemFn, Vec<rt_compiler::Item>) {
    let src = format!(
        "#[rt_program(ray_generation)]
        pub fn gen(#[var] mut out: RwBuffer<f32>, #[var] y: u32) {{
            let i = launch_index().x;
            let x = i as f32;
            {body}
        }}"
    );
    let f: syn::ItemFn = syn::parse_str(&src).unwrap();
    let file: syn::File = syn::parse_str(ITEMS).unwrap();
    let deps = file
        .items
        .iter()
        .map(|it| match it {
            syn::Item::Fn(f) => rt_compiler::Item::Function(f.clone()),
            _ => unreachable!(),
        })
        .collect();
    (f, deps)
}

fn errors(e: rt_compiler::Errors) -> String {
    e.0.iter().filter(|e| !e.is_silent()).map(|e| e.message.clone()).collect::<Vec<_>>().join("\n")
}

#[test]
fn assertions_on_raise_and_off_leave_nothing() {
    let (f, deps) = program("debug_assert!(y < 10, \"y is small\"); out[i] = checked(x - 1.0);");
    let on = lower(Entry::Program(rt_compiler::Kind::RayGeneration, &f), &deps).map_err(errors).unwrap();
    let off = lower_without_debug_assertions(Entry::Program(rt_compiler::Kind::RayGeneration, &f), &deps)
        .map_err(errors)
        .unwrap();
    let throws = |w: &str| w.matches("rt_throw(").count() - w.matches("fn rt_throw(").count();
    // One in the program, one in the helper.
    assert_eq!(throws(&on.wgsl), 2, "{}", on.wgsl);
    assert!(on.program.contains("< 10u"), "{}", on.program);
    assert_eq!(throws(&off.wgsl), 0, "{}", off.wgsl);
    assert!(!off.program.contains("10u"), "the condition is not evaluated: {}", off.program);
    assert!(off.wgsl.contains("fn rtf_checked("));
}

#[test]
fn a_message_is_one_literal_and_only_programs_that_raise_assert() {
    let (f, deps) = program("debug_assert!(y < 10, \"y is {}\", y); out[i] = x;");
    let e = lower(Entry::Program(rt_compiler::Kind::RayGeneration, &f), &deps).map(|_| ()).map_err(errors);
    assert_eq!(
        e.unwrap_err(),
        "a formatted `debug_assert!` message is not supported in ray programs: write the message as one string \
         literal: `debug_assert!(cond, \"why\")` (the GPU has no strings; the exception's record says where)"
    );
    let (f, deps) = program("debug_assert!(y + 1); out[i] = x;");
    let e = lower(Entry::Program(rt_compiler::Kind::RayGeneration, &f), &deps).map(|_| ()).map_err(errors);
    assert!(e.unwrap_err().contains("bool"), "the condition is typed as `if`'s");
    // Still typed with assertions off: the lowering with them on reports it
    // (a program is lowered both ways only when that one lowered).
}

#[test]
fn the_cpu_copy_calls_rt_stds_assertion_with_the_condition_rewritten() {
    let mut f: syn::ItemFn = syn::parse_str("fn f(a: u32, b: u32) { debug_assert!(a + b > 2, \"why\"); }").unwrap();
    rt_compiler::cpu_semantics::rewrite_fn(&mut f);
    let got = quote::quote!(#f).to_string();
    assert!(
        got.contains(":: rt_std :: __rt_debug_assert ! (:: rt_std :: arith :: add (a , b) > 2 , \"why\")"),
        "{got}"
    );
}
