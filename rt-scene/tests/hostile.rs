//! Files from strangers: every way a mutated glTF, OBJ or MTL broke the
//! loader (a panic inside the `gltf` crate or `tobj`, exponential
//! expansion, unbounded reads, reads outside the model's folder), each
//! refused through `rt_scene::load` with its exact message, and what the
//! formats allow that was refused, now read.

mod common;

use common::{base, edited, load_text, refused, temp_dir};
use glam::Vec3;
use rt_runtime::Context;
use rt_scene::LoadLimits;

#[test]
fn the_base_file_loads_and_moves() {
    let (_, loaded) = load_text("base.gltf", &base(), &LoadLimits::default());
    let loaded = loaded.unwrap();
    assert_eq!(loaded.info.instances, 3);
    let animation = loaded.animation.expect("node 1 moves");
    assert_eq!(animation.instance_matrices(1.0)[1].w_axis.truncate(), Vec3::X);
}

#[test]
fn what_the_gltf_crate_would_panic_on_is_refused_first() {
    let cases: [common::Case; 9] = [
        (
            "count_zero.gltf",
            &[(r#""bufferView":4,"componentType":5126,"count":2"#, r#""bufferView":4,"componentType":5126,"count":0"#)],
            "accessors[4]: has a count of 0 (the specification asks for at least 1)",
        ),
        (
            "stride.gltf",
            &[(r#""byteOffset":0,"byteLength":36}"#, r#""byteOffset":0,"byteLength":36,"byteStride":4}"#)],
            "accessors[0]: its elements are 12 bytes, but bufferViews[0] has byteStride 4",
        ),
        (
            "float_indices.gltf",
            &[(r#""componentType":5123"#, r#""componentType":5126"#)],
            "meshes[0].primitives[0].indices: accessors[1] is Scalar of F32, but indices must be Scalar of U8, U16, U32",
        ),
        (
            "signed_indices.gltf",
            &[(r#""componentType":5123"#, r#""componentType":5122"#)],
            "meshes[0].primitives[0].indices: accessors[1] is Scalar of I16, but indices must be Scalar of U8, U16, U32",
        ),
        (
            "uint_texcoords.gltf",
            &[(r#""bufferView":2,"componentType":5126"#, r#""bufferView":2,"componentType":5125"#)],
            "meshes[0].primitives[0].attributes.TEXCOORD_0: accessors[2] is Vec2 of U32, but TEXCOORD_n must be \
             Vec2 of F32, U8, U16",
        ),
        (
            "uint_rotation.gltf",
            &[
                (r#""path":"translation""#, r#""path":"rotation""#),
                (r#""output":4"#, r#""output":5"#),
                (r#""bufferView":5,"componentType":5126"#, r#""bufferView":5,"componentType":5125"#),
            ],
            "animations[0].channels[0] output: accessors[5] is Vec4 of U32, but a rotation must be Vec4 of F32, I8, \
             U8, I16, U16",
        ),
        (
            "position_99.gltf",
            &[(r#""POSITION":0"#, r#""POSITION":99"#)],
            "meshes[0].primitives[0]: attributes.Positions names accessors[99], but the file's accessors end at \
             accessors[5]",
        ),
        (
            "target_50.gltf",
            &[(r#""node":1,"path""#, r#""node":50,"path""#)],
            "animations[0].channels[0]: target.node names nodes[50], but the file's nodes end at nodes[2]",
        ),
        (
            "bogus_path.gltf",
            &[(r#""path":"translation""#, r#""path":"bogus""#)],
            "animations[0].channels[0]: target.path is not a value the glTF specification allows",
        ),
    ];
    for (name, edits, problem) in cases {
        assert_eq!(refused(name, &edited(edits)), problem, "{name}");
    }
}

#[test]
fn accessors_of_types_the_specification_forbids_are_refused() {
    let cases: [common::Case; 3] = [
        (
            "short_positions.gltf",
            &[(r#""bufferView":0,"componentType":5126"#, r#""bufferView":0,"componentType":5123"#)],
            "meshes[0].primitives[0].attributes.POSITION: accessors[0] is Vec3 of U16, but POSITION must be Vec3 of F32",
        ),
        (
            "vec2_positions.gltf",
            &[(r#""count":3,"type":"VEC3""#, r#""count":3,"type":"VEC2""#)],
            "meshes[0].primitives[0].attributes.POSITION: accessors[0] is Vec2 of F32, but POSITION must be Vec3 of F32",
        ),
        (
            "vec3_times.gltf",
            &[(r#""count":2,"type":"SCALAR""#, r#""count":2,"type":"VEC3""#)],
            "animations[0].channels[0] input: accessors[3] is Vec3 of F32, but an animation's input must be Scalar of F32",
        ),
    ];
    for (name, edits, problem) in cases {
        assert_eq!(refused(name, &edited(edits)), problem, "{name}");
    }
}

#[test]
fn the_node_graph_must_be_a_forest() {
    let cases: [common::Case; 4] = [
        (
            "shared.gltf",
            &[(r#"{"mesh":0}],"#, r#"{"mesh":0,"children":[1]}],"#)],
            "nodes[2]: is a second parent of nodes[1], a child of nodes[0] already (a node has one parent)",
        ),
        ("twice.gltf", &[(r#""children":[1]"#, r#""children":[1,1]"#)], "nodes[0]: lists nodes[1] twice as a child"),
        (
            "cycle.gltf",
            &[
                (r#""scenes":[{"nodes":[0,2]}]"#, r#""scenes":[{"nodes":[2]}]"#),
                (r#""translation":[0,0,1]"#, r#""translation":[0,0,1],"children":[0]"#),
            ],
            "nodes[0]: is its own ancestor (the node graph has a cycle)",
        ),
        (
            "scene_child.gltf",
            &[(r#""scenes":[{"nodes":[0,2]}]"#, r#""scenes":[{"nodes":[0,1]}]"#)],
            "scenes[0]: lists nodes[1], which is a child of nodes[0] (a scene lists root nodes)",
        ),
    ];
    for (name, edits, problem) in cases {
        assert_eq!(refused(name, &edited(edits)), problem, "{name}");
    }
}

/// Nodes that share children, 24 levels deep: 2^24 paths. Refused at
/// once, where it used to expand each path (gigabytes, minutes).
#[test]
fn shared_children_are_refused_before_any_expansion() {
    let mut nodes = vec![r#"{"mesh":0}"#.to_string()];
    for i in 1..=24 {
        nodes.push(format!(r#"{{"children":[{},{}]}}"#, i - 1, i - 1));
    }
    let text = edited(&[
        (r#"{"mesh":0,"children":[1]},{"mesh":0,"translation":[0,0,1]},{"mesh":0}"#, &nodes.join(",")),
        (r#""scenes":[{"nodes":[0,2]}]"#, r#""scenes":[{"nodes":[24]}]"#),
        (r#""node":1,"path""#, r#""node":0,"path""#),
    ]);
    let t = std::time::Instant::now();
    assert_eq!(refused("bomb.gltf", &text), "nodes[1]: lists nodes[0] twice as a child");
    assert!(t.elapsed().as_secs() < 5, "{:?}", t.elapsed());
}

#[test]
fn transforms_and_cameras_the_renderer_cannot_use_name_the_node() {
    let cases: [common::Case; 4] = [
        (
            "singular.gltf",
            &[(r#"{"mesh":0}],"#, r#"{"mesh":0,"matrix":[1,0,0,0, 0,0,0,0, 0,0,1,0, 0,0,0,1]}],"#)],
            "nodes[2]: its world transform is singular (determinant 0e0): a scale of zero?",
        ),
        (
            "huge.gltf",
            &[(r#"{"mesh":0}],"#, r#"{"mesh":0,"scale":[1e30,1e30,1e30]}],"#)],
            "nodes[2]: its world transform is not finite",
        ),
        (
            "far.gltf",
            &[(r#"{"mesh":0}],"#, r#"{"mesh":0,"translation":[3.4e38,0,0],"scale":[1e37,1,1]}],"#)],
            "nodes[2]: meshes[0] has vertex [1, 0, 0], which its transform moves out of f32's range",
        ),
        (
            "yfov.gltf",
            &[(
                r#"{"mesh":0}],"#,
                r#"{"mesh":0,"camera":0}],"cameras":[{"type":"perspective","perspective":{"yfov":1e39,"znear":0.1}}],"#,
            )],
            "cameras[0]: perspective.yfov inf is outside (0, pi) radians",
        ),
    ];
    for (name, edits, problem) in cases {
        assert_eq!(refused(name, &edited(edits)), problem, "{name}");
    }
}

#[test]
fn poses_at_times_and_scales_that_cannot_be_shown_are_refused() {
    let mut ctx = Context::new();
    let dir = temp_dir("poses");
    let path = dir.join("zero_scale.gltf");
    std::fs::write(&path, edited(&[(r#""path":"translation""#, r#""path":"scale""#)])).unwrap();
    let loaded = rt_scene::load(&mut ctx, &path).unwrap();
    let animation = loaded.animation.unwrap();
    let e = animation.pose(&mut ctx, f32::NAN).unwrap_err();
    assert!(e.is_bad_input());
    assert_eq!(
        e.to_string(),
        format!("{}: cannot pose the animation at time NaN: not a finite number of seconds", path.display())
    );
    // The first scale key is zero.
    let e = animation.pose(&mut ctx, 0.0).unwrap_err();
    assert!(e.is_bad_input());
    assert_eq!(
        e.to_string(),
        format!(
            "{}: nodes[1]: at 0 s, its world transform is singular (determinant 0e0): a scale of zero?",
            path.display()
        )
    );
    // The rig itself holds the first pose for a time that is not a number.
    assert_eq!(animation.instance_matrices(f32::NAN), animation.instance_matrices(0.0));
}

/// `Kd 1` (a grey, as MTL allows) panicked inside `tobj`; `obj2glb` reads
/// it, and refuses a colour that is not finite by its line.
#[test]
fn obj2glb_reads_a_one_number_colour_and_refuses_a_non_finite_one() {
    let dir = temp_dir("obj2glb");
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";
    std::fs::write(dir.join("m.obj"), obj).unwrap();
    let run = |mtl: &str| {
        std::fs::write(dir.join("m.mtl"), mtl).unwrap();
        std::process::Command::new(env!("CARGO_BIN_EXE_obj2glb"))
            .args([dir.join("m.obj"), dir.join("m.glb")])
            .output()
            .unwrap()
    };
    let out = run("newmtl m\nKd 1\n");
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    let out = run("newmtl m\nKd 1\nKs 0 NaN 0\n");
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(String::from_utf8_lossy(&out.stderr).trim_end(), "obj2glb: m.mtl:3: `Ks` has NaN, which is not finite");
}

/// Words and values quoted from a file are clipped, so a refusal stays a
/// short line however long the file makes them.
#[test]
fn quoted_words_are_clipped() {
    let e = rt_scene::obj::parse_obj(&format!("v 0 0 {}\n", "7x".repeat(500)), "long.obj", None).unwrap_err();
    assert_eq!(e.to_string(), format!("long.obj:1: a vertex has `{}...`, which is not a number", "7x".repeat(24)));
    let text = edited(&[(
        r#"{"buffer":0,"byteOffset":0,"byteLength":36}"#,
        &format!(r#"{{"buffer":"{}"}}"#, "b".repeat(900)),
    )]);
    let line = refused("long.gltf", &text);
    assert!(line.len() < 200 && line.starts_with("not valid glTF JSON: invalid type: string \"bbbb"), "{line}");
}
