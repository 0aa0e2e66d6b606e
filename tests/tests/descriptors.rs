//! The descriptors the real macros emit (compiled in this crate's library
//! from the snapshot corpus) agree with the library lowering and describe
//! the programs fully; the CPU entry runs the Rust function.

use examples::common::{Normals, Radiance};
use examples::{common, convex_hull, diffuse, envmap, normal, phong, reflections, shadows};
use glam::{Vec2, Vec3};
use rt_std::cpu::{BoundVariables, CpuArgs, CpuResult};
use rt_std::program::{ProgramKind, VariableKind};

#[test]
fn macro_wgsl_equals_the_checked_in_snapshot() {
    let programs = [
        &common::pinhole_camera::PROGRAM,
        &common::background::PROGRAM,
        &common::shadow_miss::PROGRAM,
        &common::any_hit_shadow::PROGRAM,
        &common::exception::PROGRAM,
        &normal::normal_shader::PROGRAM,
        &diffuse::diffuse::PROGRAM,
        &phong::phong::PROGRAM,
        &shadows::phong_shadowed::PROGRAM,
        &reflections::reflective::PROGRAM,
        &envmap::envmap_miss::PROGRAM,
        &convex_hull::chull_intersect::PROGRAM,
        &convex_hull::chull_bounds::PROGRAM,
        &convex_hull::glass::PROGRAM,
        &convex_hull::glass_shadow::PROGRAM,
    ];
    for p in programs {
        let path = format!("{}/snapshots/out/{}.wgsl", env!("CARGO_MANIFEST_DIR"), p.name);
        let snapshot = std::fs::read_to_string(&path).unwrap();
        let body = p.wgsl.strip_prefix(p.wgsl_prelude).map(str::to_owned);
        let expected = snapshot.split_once('\n').unwrap().1;
        // The snapshot holds the per-type stubs of the prelude too, and a
        // tracing program's resumable form after the module.
        let stubs = p.wgsl_prelude.strip_prefix(rt_compiler::lower::PRELUDE.as_str()).unwrap();
        let mut got = format!("{stubs}{}", body.unwrap());
        if let Some(r) = p.wgsl_resumable {
            got.push_str("\n// ---- resumable form ----\n");
            for f in p.wgsl_resumable_functions {
                got.push_str(f.text);
            }
            got.push_str(r);
        }
        assert_eq!(got, expected, "{}", p.name);
        assert_eq!(p.wgsl_resumable.is_some(), !p.traced_payloads.is_empty(), "{}", p.name);
        assert!(p.file.ends_with(".rs") && p.line > 0, "{}: {}:{}", p.name, p.file, p.line);
    }
}

#[test]
fn descriptor_describes_the_program() {
    let p = &shadows::phong_shadowed::PROGRAM;
    assert_eq!(p.kind, ProgramKind::ClosestHit);
    assert_eq!(p.wgsl_entry, "rtp_phong_shadowed");
    assert_eq!(p.payload.unwrap().rust, "Radiance");
    assert_eq!(p.payload.unwrap().words, 5);
    assert_eq!(p.attributes.unwrap().wgsl, "Normals");
    let names: Vec<&str> = p.variables.iter().map(|v| v.name).collect();
    assert_eq!(
        names,
        ["ka", "kd", "ks", "phong_exp", "ambient_light_color", "lights", "scene_epsilon", "top_shadower"]
    );
    let lights = p.variables.iter().find(|v| v.name == "lights").unwrap();
    match lights.kind {
        VariableKind::Buffer { element, dimensions, writable } => {
            assert_eq!((element.rust, element.words, dimensions, writable), ("BasicLight", 7, 1, false));
            assert_eq!(element.fields[2].offset_words, 6);
        }
        other => panic!("lights is {other:?}"),
    }
    assert_eq!(p.variables.iter().find(|v| v.name == "top_shadower").unwrap().kind, VariableKind::Object);
    assert_eq!(p.traced_payloads.iter().map(|t| t.rust).collect::<Vec<_>>(), ["Shadow"]);
    for i in ["current_ray", "rt_trace", "rt_transform_normal", "t_hit"] {
        assert!(p.intrinsics.contains(&i), "{i} missing from {:?}", p.intrinsics);
    }
    assert!(p.file.ends_with("shadows.rs"), "{}", p.file);
    assert_eq!(p.line, 50);
    let e = &rt_tests::printf::printf::PROGRAM;
    // Its own three formats and its helper's, each with its argument types.
    assert_eq!(e.printf.len(), 4);
    let depth = e.printf.iter().find(|f| f.format == "depth {} importance {} verbose {}").unwrap();
    assert_eq!(depth.args, ["i32", "f32", "bool"]);
    let raw = e.printf.iter().find(|f| f.format == "{{raw}} {} {} {}").unwrap();
    assert_eq!(raw.args, ["vec2<u32>", "vec3<i32>", "bool"]);
}

#[test]
fn descriptor_records_the_sites_per_depth_clones_rename() {
    use rt_std::program::{WgslName, WgslSite};
    // `glass` traces twice (reflection and refraction) and calls one helper
    // that does not trace.
    let p = &convex_hull::glass::PROGRAM;
    assert_eq!(WgslSite::traces_per_payload(p.wgsl_program_sites), [("Radiance", 2)]);
    assert_eq!(WgslSite::helpers_called(p.wgsl_program_sites), ["rtf_fresnel_schlick"]);
    assert_eq!(p.wgsl_program_sites[0].name, WgslName::Definition);
    // Every site ends where its name does, in the text it was recorded for.
    let helper = p.wgsl_functions.iter().find(|f| f.name == "rtf_fresnel_schlick").unwrap();
    assert_eq!(helper.sites.iter().map(|s| s.name).collect::<Vec<_>>(), [WgslName::Definition]);
    for (text, sites, own) in
        [(p.wgsl_program, p.wgsl_program_sites, p.wgsl_entry), (helper.text, helper.sites, helper.name)]
    {
        for s in sites {
            let name = match s.name {
                WgslName::Definition => format!("fn {own}"),
                WgslName::Trace(payload) => format!("rt_trace_{payload}"),
                WgslName::Call(h) | WgslName::Dispatch(h) => h.to_string(),
            };
            let (before, after) = text.split_at(s.end as usize);
            assert!(before.ends_with(&name) && after.starts_with('('), "{s:?} in {own}");
        }
    }
    // Types and resumable forms have none; a program that does not trace or
    // call anything only its own name.
    assert!(p.wgsl_types.iter().chain(p.wgsl_resumable_functions).all(|t| t.sites.is_empty()));
    let miss = &common::background::PROGRAM;
    assert_eq!(miss.wgsl_program_sites.iter().map(|s| s.name).collect::<Vec<_>>(), [WgslName::Definition]);
}

#[test]
fn cpu_entry_runs_the_rust_function() {
    let mut prd = Radiance { result: Vec3::ZERO, importance: 1.0, depth: 0 };
    let bg = Vec3::new(0.1, 0.2, 0.3);
    let vars = (common::background::PROGRAM.cpu_bind)(&[&bg]).unwrap();
    let mut args = CpuArgs { payload: Some(&mut prd), attributes: None, primitive: 0, variables: &vars };
    assert_eq!((common::background::PROGRAM.cpu)(&mut args), CpuResult::Unit);
    assert_eq!(prd.result, bg);

    // The normal shader with identity transforms: n * 0.5 + 0.5.
    let mut prd = Radiance::default();
    let mut attr = Normals { geometric_normal: Vec3::Z, shading_normal: Vec3::new(0.0, 3.0, 0.0) };
    let mut args = CpuArgs {
        payload: Some(&mut prd),
        attributes: Some(&mut attr),
        primitive: 0,
        variables: &BoundVariables::NONE,
    };
    (normal::normal_shader::PROGRAM.cpu)(&mut args);
    assert_eq!(prd.result, Vec3::new(0.5, 1.0, 0.5));

    let lo = Vec3::splat(-1.0);
    let hi = Vec3::new(1.0, 2.0, 3.0);
    let vars = (convex_hull::chull_bounds::PROGRAM.cpu_bind)(&[&lo, &hi]).unwrap();
    let mut args = CpuArgs { payload: None, attributes: None, primitive: 3, variables: &vars };
    assert_eq!((convex_hull::chull_bounds::PROGRAM.cpu)(&mut args), CpuResult::Aabb(rt_std::Aabb::new(lo, hi)));
}

#[test]
fn cpu_bind_checks_each_variable_once() {
    let bg = Vec3::ONE;
    let wrong = 1.0f32;
    // The declared type is checked at binding, with the variable's position.
    let e = (common::background::PROGRAM.cpu_bind)(&[&wrong]).unwrap_err();
    assert_eq!(e.index, 0);
    assert!(e.expected.ends_with("Vec3"), "{}", e.expected);
    // So is the count.
    assert!((common::background::PROGRAM.cpu_bind)(&[]).is_err());
    assert!((common::background::PROGRAM.cpu_bind)(&[&bg, &bg]).is_err());
    // Values bound to one program's types are not read as another's.
    let vars = (common::background::PROGRAM.cpu_bind)(&[&bg]).unwrap();
    let mut args = CpuArgs { payload: None, attributes: None, primitive: 0, variables: &vars };
    let r =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| (convex_hull::chull_bounds::PROGRAM.cpu)(&mut args)));
    assert!(r.is_err());
}

#[test]
fn user_structs_round_trip_through_heap_words() {
    use rt_std::RtData;
    let l = common::BasicLight { pos: Vec3::new(1.0, 2.0, 3.0), color: Vec3::ONE, casts_shadow: -7 };
    let mut words = [0u32; 7];
    l.write_words(&mut words);
    assert_eq!(words[6], (-7i32) as u32);
    assert_eq!(common::BasicLight::read_words(&words), l);
    assert_eq!(<common::BasicLight as RtData>::LAYOUT.words, 7);
    // In place, field by field (how the CPU backend refills attributes).
    let mut m = common::BasicLight { pos: Vec3::splat(9.0), color: Vec3::ZERO, casts_shadow: 5 };
    m.read_words_into(&words);
    assert_eq!(m, l);
    // Vectors and matrices in place, and from a slice longer than they are.
    let mut v = Vec3::ZERO;
    v.read_words_into(&words[3..]);
    assert_eq!(v, Vec3::ONE);
    let mat = glam::Mat3::from_cols_array(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    let mut mw = [0u32; 10];
    mat.write_words(&mut mw);
    assert_eq!(mw[9], 0);
    assert_eq!(glam::Mat3::read_words(&mw), mat);
    // A short slice takes what fits (the rest zero), as before.
    assert_eq!(Vec3::read_words(&words[..2]), Vec3::new(1.0, 2.0, 0.0));
}

/// Attributes with the built-in triangle fields and others beside them; one
/// built-in's type is written as a path. (A field of a built-in's name but
/// another type is a compile error: `compile_fail/attribute_builtin_misspelled.rs`.)
#[rt_std::prelude::rt_attributes]
pub struct Mixed {
    pub weight: f32,
    pub geometric_normal: Vec3,
    pub weights: Vec3,
    pub frame: glam::Mat3,
    pub texcoord: glam::Vec2,
    pub spare: [f32; 2],
}

#[test]
fn triangle_hits_fill_the_built_in_attribute_fields_and_zero_the_rest() {
    use rt_std::cpu::TriangleBuiltins;
    use rt_std::{Attributes, RtData};
    let t = TriangleBuiltins {
        geometric_normal: Vec3::new(1.0, 2.0, 3.0),
        shading_normal: Vec3::new(4.0, 5.0, 6.0),
        texcoord: Vec2::new(0.25, 0.5),
        barycentrics: Vec2::new(0.125, 0.375),
    };
    let mut m = Mixed {
        weight: 7.0,
        geometric_normal: Vec3::splat(9.0),
        weights: Vec3::splat(9.0),
        frame: glam::Mat3::IDENTITY,
        texcoord: Vec2::splat(9.0),
        spare: [9.0; 2],
    };
    m.set_triangle(&t);
    let expected = Mixed {
        weight: 0.0,
        geometric_normal: t.geometric_normal,
        weights: Vec3::ZERO,
        frame: glam::Mat3::ZERO,
        texcoord: t.texcoord,
        spare: [0.0; 2],
    };
    assert_eq!(m, expected);
    // The generated fill agrees with the layout: the same value through heap
    // words, placed by the layout's fields (what the megakernel does too).
    let words = rt_std::data::triangle_words(&<Mixed as RtData>::LAYOUT, &t);
    assert_eq!(Mixed::read_words(&words), expected);
}
