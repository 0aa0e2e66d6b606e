//! naga's validation errors come back at the Rust expression that produced
//! the offending WGSL, through the source map.

#[test]
fn a_naga_error_points_at_the_rust_expression() {
    // The checker lets a constant index through; naga rejects it.
    let src = r#"
        #[rt_program(ray_generation)]
        pub fn gen() {
            let a = [1.0f32, 2.0, 3.0];
            let x = a[7];
            let _ = x;
        }
    "#;
    let errors = rt_compiler::lower_source(src, "gen").expect_err("naga rejects a[7]");
    let e = &errors.0[0];
    assert!(e.message.contains("naga rejects the WGSL lowered from this expression"), "{}", e.message);
    // The span is the index expression (or its operand), not the function.
    let text = e.span.source_text().unwrap_or_default();
    assert!(text == "a[7]" || text == "7" || text == "a", "error at `{text}`: {}", e.message);
}
