//! `let mut o = None;` with no type written: typed by the first `Option`
//! assigned to `o` after it, as rustc infers it; still an error where
//! nothing assigns one.

mod common;

fn lower(body: &str) -> Result<rt_compiler::Lowered, String> {
    common::lower("", body)
}

/// The WGSL line declaring the local `name`.
fn declaration<'a>(l: &'a rt_compiler::Lowered, name: &str) -> &'a str {
    let prefix = format!("var {name}: ");
    l.wgsl.lines().map(str::trim).find(|line| line.starts_with(&prefix)).unwrap_or_else(|| panic!("{}", l.wgsl))
}

#[test]
fn a_later_assignment_types_the_none() {
    let l = lower(
        "let mut best = None;
         for k in 0..4u32 { let d = x - k as f32; if d > 0.0 { best = Some(d); } }
         let mut n = None;
         if x > 1.0 { n = Some(3); }
         let m = n.unwrap_or(0) + y;
         out[i] = best.unwrap_or(-1.0) + m as f32;",
    )
    .unwrap();
    assert_eq!(declaration(&l, "best"), "var best: rt_option_f32_ = rt_option_f32_();");
    // The literal's type comes from its later use with a `u32`.
    assert_eq!(declaration(&l, "n"), "var n: rt_option_u32_ = rt_option_u32_();");
}

#[test]
fn one_none_local_assigned_before_another_leaves_its_type_to_its_own_probe() {
    let l = lower(
        "let mut a = None;
         let mut b = None;
         for k in 0..3u32 { b = Some(k); a = Some(x); }
         out[i] = a.unwrap_or(0.0) + b.unwrap_or(0) as f32;",
    )
    .unwrap();
    assert_eq!(declaration(&l, "a"), "var a: rt_option_f32_ = rt_option_f32_();");
    assert_eq!(declaration(&l, "b"), "var b: rt_option_u32_ = rt_option_u32_();");
}

#[test]
fn without_an_assignment_the_none_needs_a_type() {
    assert_eq!(
        lower("let mut o = None; if x > 1.0 { out[i] = 1.0; } out[i] = o.unwrap_or(2.0);").unwrap_err(),
        "the type of this `None` is not known here: annotate the binding (`let o: Option<f32> = None;`) or write `None::<f32>`"
    );
}
