//! `#[rt_trait]`s through the compiler alone: trait impls lowered as
//! methods of their type, default methods and constants, calls resolved by
//! the receiver's type, generics bounded by a trait, and the errors that
//! stay.

fn lower(items: &str, body: &str) -> Result<rt_compiler::Lowered, String> {
    let src = format!(
        "use rt_std::prelude::*;
        {items}
        #[rt_program(ray_generation)]
        pub fn gen(#[var] mut out: RwBuffer<f32>) {{
            let i = launch_index().x;
            let x = i as f32;
            {body}
        }}"
    );
    rt_compiler::lower_source(&src, "gen")
        .map_err(|e| e.0.iter().filter(|e| !e.is_silent()).map(|e| e.message.clone()).collect::<Vec<_>>().join("\n"))
}

const BSDFS: &str = "
    #[rt_trait]
    pub trait Bsdf {
        const GAIN: f32 = 1.0;
        fn albedo(&self) -> f32;
        fn eval(&self, c: f32) -> f32 { self.albedo() * c * Self::GAIN }
    }
    #[rt_struct(impl Bsdf)]
    pub struct Lambert { pub a: f32 }
    #[rt_struct(impl, impl Bsdf)]
    pub struct Mirror { pub k: f32 }
    #[rt_impl]
    impl Bsdf for Lambert {
        fn albedo(&self) -> f32 { self.a }
    }
    #[rt_impl]
    impl Bsdf for Mirror {
        const GAIN: f32 = 2.0;
        fn albedo(&self) -> f32 { self.k * 0.5 }
        fn eval(&self, c: f32) -> f32 { c - self.albedo() }
    }
    #[rt_impl]
    impl Mirror {
        pub fn new(k: f32) -> Mirror { Mirror { k } }
    }
    #[rt_function]
    pub fn shade<B: Bsdf>(b: B, c: f32) -> f32 { b.eval(c) + B::GAIN }";

fn functions(l: &rt_compiler::Lowered) -> Vec<String> {
    let mut fns: Vec<String> = l
        .wgsl
        .lines()
        .filter_map(|line| line.strip_prefix("fn "))
        .filter(|f| f.starts_with("rtm_") || f.starts_with("rtf_"))
        .map(|rest| rest.split('(').next().unwrap().to_string())
        .collect();
    fns.sort();
    fns
}

#[test]
fn trait_methods_are_methods_of_their_type_with_the_defaults_filled_in() {
    let l = lower(
        BSDFS,
        "let l = Lambert { a: x };
         let m = Mirror::new(x);
         out[i] = l.eval(2.0) + m.eval(3.0) + Lambert::GAIN + Mirror::GAIN + shade(l, 1.0) + shade(m, 1.0);",
    )
    .unwrap();
    assert_eq!(
        functions(&l),
        [
            "rtf_shade__Lambert",
            "rtf_shade__Mirror",
            "rtm_Lambert__albedo",
            "rtm_Lambert__eval",
            "rtm_Mirror__albedo",
            "rtm_Mirror__eval",
            "rtm_Mirror__new"
        ]
    );
    // The default `eval` reads the type's own constant.
    assert!(l.wgsl.contains("const Lambert__GAIN: f32 = 1.0f;"), "{}", l.wgsl);
    assert!(l.wgsl.contains("const Mirror__GAIN: f32 = 2.0f;"), "{}", l.wgsl);
    let eval = l.wgsl.split("fn rtm_Lambert__eval").nth(1).unwrap();
    assert!(eval.split("\n}").next().unwrap().contains("Lambert__GAIN"), "{eval}");
}

#[test]
fn dyn_trait_points_at_callables() {
    let e = lower(
        &format!("{BSDFS}\n#[rt_function] pub fn f(b: &dyn Bsdf) -> f32 {{ b.albedo() }}"),
        "out[i] = f(&Lambert { a: x });",
    )
    .unwrap_err();
    assert!(e.starts_with("a trait object (`dyn`) is not supported in ray programs"), "{e}");
    assert!(e.contains("`Callable` id"), "{e}");
}

#[test]
fn recursion_through_a_trait_method_is_refused() {
    let e = lower(
        "#[rt_trait] pub trait Walk { fn step(&self, n: u32) -> f32; }
         #[rt_struct(impl Walk)] pub struct W { pub v: f32 }
         #[rt_impl] impl Walk for W { fn step(&self, n: u32) -> f32 { if n == 0 { self.v } else { self.step(n - 1) } } }",
        "out[i] = W { v: x }.step(3);",
    )
    .unwrap_err();
    assert_eq!(
        e,
        "recursion (`W::step` calls itself) is not supported in ray programs: WGSL has no recursion; rewrite it as a loop"
    );
}
