//! The contract (`rt-abi`) holds on both sides: every WGSL function of its
//! intrinsic and runtime-function rows has, in the megakernel the runtime
//! links, exactly the signature the compiler's stub prelude gave programs at
//! `cargo build`. Both modules are parsed with naga and their functions
//! compared type by type, so a runtime body that drifts from its row (a
//! renamed function, a parameter added or retyped) fails here, not at the
//! first GPU launch that calls it.

use glam::Vec4;
use rt_runtime::*;
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn fill(#[var] mut out: RwBuffer2d<Vec4>) {
    out[launch_index()] = Vec4::ONE;
}

#[rt_payload]
pub struct Nothing {
    pub seen: f32,
}

#[rt_program(miss)]
pub fn nothing(prd: &mut Nothing) {
    prd.seen = 1.0;
}

/// The functions of `module` by name, each as its parameter types and return
/// type in words (structs by name, other types by their naga form).
fn signatures(module: &naga::Module) -> std::collections::HashMap<String, (Vec<String>, Option<String>)> {
    let ty = |h: naga::Handle<naga::Type>| {
        let t = &module.types[h];
        match &t.inner {
            naga::TypeInner::Struct { .. } => t.name.clone().unwrap_or_default(),
            other => format!("{other:?}"),
        }
    };
    module
        .functions
        .iter()
        .filter_map(|(_, f)| {
            let params = f.arguments.iter().map(|a| ty(a.ty)).collect();
            Some((f.name.clone()?, (params, f.result.as_ref().map(|r| ty(r.ty)))))
        })
        .collect()
}

#[test]
fn the_linked_megakernel_implements_every_function_of_the_contract_as_the_stubs_declare_it() {
    let mut ctx = Context::new();
    ctx.set_backend(Backend::Wgpu);
    let rg = ctx.create_program(&fill::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&nothing::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, 2, 2).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.launch(0, 2, 2).unwrap();
    let linked = naga::front::wgsl::parse_str(ctx.linked_wgsl().unwrap()).expect("the linked kernel parses");
    let stubs = naga::front::wgsl::parse_str(&rt_compiler::lower::PRELUDE).expect("the stub prelude parses");
    let (linked, stubs) = (signatures(&linked), signatures(&stubs));
    let mut checked = 0;
    for f in rt_abi::intrinsics::wgsl_functions() {
        let stub = stubs.get(f.name).unwrap_or_else(|| panic!("the stub prelude has no `{}`", f.name));
        let real = linked.get(f.name).unwrap_or_else(|| panic!("the runtime's prelude has no `{}`", f.name));
        assert_eq!(real, stub, "`{}`: the runtime's signature, then the contract's", f.name);
        checked += 1;
    }
    assert!(checked >= 20, "only {checked} functions in the contract");
}
