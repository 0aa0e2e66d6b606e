//! What the compiler's own tests share: a ray-generation program around a
//! body, lowered with the items given beside it.

/// Lowers `body` as the body of `gen(#[var] mut out: RwBuffer<f32>, #[var]
/// y: u32)`, with `i` (the launch index's `x`) and `x` (it as `f32`) in
/// scope and `items` beside the program; the errors' messages, one a line.
pub fn lower(items: &str, body: &str) -> Result<rt_compiler::Lowered, String> {
    let src = format!(
        "use rt_std::prelude::*;
        {items}
        #[rt_program(ray_generation)]
        pub fn gen(#[var] mut out: RwBuffer<f32>, #[var] y: u32) {{
            let i = launch_index().x;
            let x = i as f32;
            {body}
        }}"
    );
    rt_compiler::lower_source(&src, "gen")
        .map_err(|e| e.0.iter().filter(|e| !e.is_silent()).map(|e| e.message.clone()).collect::<Vec<_>>().join("\n"))
}
