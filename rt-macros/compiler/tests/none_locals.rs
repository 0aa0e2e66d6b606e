//! `let o = None;` with no type written: typed by the first use of `o`
//! after it that fixes its type (an `Option` assigned to it, `o` passed to
//! a parameter, returned, compared with an `Option`, given a value by
//! `unwrap_or`), as rustc infers it; still an error where nothing fixes
//! it.

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

/// The WGSL line declaring the constant `name`.
fn constant<'a>(l: &'a rt_compiler::Lowered, name: &str) -> &'a str {
    let prefix = format!("let {name}: ");
    l.wgsl.lines().map(str::trim).find(|line| line.starts_with(&prefix)).unwrap_or_else(|| panic!("{}", l.wgsl))
}

const ITEMS: &str = "
    #[rt_function] pub fn or_one(o: Option<f32>) -> f32 { o.unwrap_or(1.0) }
    #[rt_function] pub fn first(x: u32) -> Option<u32> {
        let o = None;
        if x > 3 { return Some(x); }
        o
    }
    #[rt_function] pub fn none_above(x: u32) -> Option<u32> {
        let n = None;
        if x > 3 { return n; }
        Some(x)
    }";

#[test]
fn a_later_use_where_an_option_of_a_known_type_is_wanted_types_the_none() {
    let l = common::lower(
        ITEMS,
        "let a = None;
         let m0 = or_one(a);
         let b = None;
         let m = b.unwrap_or(y) + first(y).unwrap_or(0) + none_above(y).unwrap_or(1);
         let d = None;
         let s = d == Some(y);
         let mut c = None;
         let k = c.unwrap_or(2.0);
         if x > 2.0 { c = Some(x); }
         out[i] = m0 + m as f32 + k + s as u32 as f32 + c.unwrap_or(0.0);",
    );
    let l = l.unwrap();
    assert_eq!(constant(&l, "a"), "let a: rt_option_f32_ = rt_option_f32_();");
    assert_eq!(constant(&l, "b"), "let b: rt_option_u32_ = rt_option_u32_();");
    assert_eq!(declaration(&l, "c"), "var c: rt_option_f32_ = rt_option_f32_();");
    assert_eq!(constant(&l, "d"), "let d: rt_option_u32_ = rt_option_u32_();");
    // The helpers' `o` and `n`, typed by their result.
    assert!(l.wgsl.contains("let o: rt_option_u32_ = rt_option_u32_();"), "{}", l.wgsl);
    assert!(l.wgsl.contains("let n: rt_option_u32_ = rt_option_u32_();"), "{}", l.wgsl);
}

#[test]
fn without_a_use_that_fixes_it_the_none_needs_a_type() {
    assert_eq!(
        lower("let mut o = None; if x > 1.0 { out[i] = 1.0; } if o.is_none() { out[i] = 2.0; }").unwrap_err(),
        "the type of this `None` is not known here: annotate the binding (`let o: Option<f32> = None;`) or write `None::<f32>`"
    );
}
