//! Type aliases: replaced by what they stand for before the lowering, in a
//! body's scope as Rust scopes them; a cycle and a wrong count of
//! arguments are errors naming the alias.

mod common;

/// The WGSL line declaring the local `name`, without `let` or `var`.
fn declaration<'a>(l: &'a rt_compiler::Lowered, name: &str) -> &'a str {
    let prefix = format!("{name}: ");
    l.wgsl
        .lines()
        .filter_map(|line| line.trim().strip_prefix("let ").or_else(|| line.trim().strip_prefix("var ")))
        .find(|line| line.starts_with(&prefix))
        .unwrap_or_else(|| panic!("{}", l.wgsl))
}

#[test]
fn an_alias_is_the_type_it_stands_for() {
    let l = common::lower(
        "#[rt_type] pub type Color = Vec3;
         #[rt_type] pub type Tint = Color;
         #[rt_type] pub type Row<T> = [T; 3];",
        "let c: Tint = Color::splat(x);
         let r: Row<u32> = [1, 2, y];
         out[i] = c.x + r[2] as f32;",
    )
    .unwrap();
    assert_eq!(declaration(&l, "c"), "c: vec3<f32> = vec3<f32>(x);");
    assert!(declaration(&l, "r").starts_with("r: array<u32, 3> = "), "{}", l.wgsl);
}

#[test]
fn an_alias_in_a_body_holds_in_its_block() {
    // The inner block's `V` shadows the outer one, as in Rust.
    let l = common::lower(
        "",
        "type V = Vec2;
         let a = V::new(x, 1.0);
         let b = { type V = Vec4; V::splat(x) };
         out[i] = a.y + b.w;",
    )
    .unwrap();
    assert!(declaration(&l, "a").starts_with("a: vec2<f32>"), "{}", l.wgsl);
    assert!(declaration(&l, "b").starts_with("b: vec4<f32>"), "{}", l.wgsl);
}

#[test]
fn a_cycle_of_aliases_is_an_error_not_a_hang() {
    let e = common::lower("#[rt_type] pub type A = B;\n#[rt_type] pub type B = A;", "let a: A = 1.0; out[i] = a;")
        .unwrap_err();
    assert_eq!(e, "this type alias stands for itself, through other aliases");
}

#[test]
fn an_alias_given_the_wrong_count_of_arguments_says_so() {
    let e =
        common::lower("#[rt_type] pub type Row<T> = [T; 3];", "let r: Row = [x, x, x]; out[i] = r[0];").unwrap_err();
    assert_eq!(e, "the type alias `Row` takes 1 type argument, and 0 are given");
}
