//! glTF node animation: a file written here whose node is moved by
//! translation, rotation and scale channels (linear, step and cubic-spline
//! keys) poses its instance exactly where the keys say, holds the first
//! and last keys outside them, sets the transforms of a context (and only
//! of the instances that move), and refuses bad channels by name.

use glam::{Mat4, Quat, Vec3, Vec4};
use rt_runtime::{Context, TriangleMesh};
use rt_scene::glb::GltfBuilder;

fn triangle() -> TriangleMesh {
    TriangleMesh { positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y], indices: vec![[0, 1, 2]], ..Default::default() }
}

/// A still node (at x = -5) and a moving one: translated from the origin to
/// (2, 0, 0) over 0..1 s (linear), turned a quarter about y at 0.5 s
/// (step), scaled from 1 to 3 over 1..2 s (cubic spline, zero tangents).
fn moving() -> GltfBuilder {
    let mut b = GltfBuilder::new();
    let mesh = b.mesh("tri", &triangle(), &[]);
    b.node(mesh, Mat4::from_translation(Vec3::new(-5.0, 0.0, 0.0)));
    let node = b.trs_node(mesh, Vec3::ZERO, Quat::IDENTITY, Vec3::ONE);
    b.animate(node, "translation", "LINEAR", &[0.0, 1.0], &[Vec4::ZERO, Vec4::new(2.0, 0.0, 0.0, 0.0)]);
    let quarter = Quat::from_rotation_y(std::f32::consts::FRAC_PI_2);
    b.animate(node, "rotation", "STEP", &[0.0, 0.5], &[Quat::IDENTITY.into(), quarter.into()]);
    let (one, three) = (Vec4::new(1.0, 1.0, 1.0, 0.0), Vec4::new(3.0, 3.0, 3.0, 0.0));
    b.animate(node, "scale", "CUBICSPLINE", &[1.0, 2.0], &[Vec4::ZERO, one, Vec4::ZERO, Vec4::ZERO, three, Vec4::ZERO]);
    b
}

fn close(a: Mat4, b: Mat4) -> bool {
    a.abs_diff_eq(b, 1e-5)
}

#[test]
fn keys_pose_the_instance_and_hold_outside_their_times() {
    let asset = rt_scene::gltf::parse(&moving().to_glb(), "moving.glb", None).unwrap();
    assert!(asset.warnings.is_empty(), "{:?}", asset.warnings);
    assert!(asset.rig.is_animated());
    assert_eq!(asset.rig.time_range(), Some((0.0, 2.0)));
    let quarter = Quat::from_rotation_y(std::f32::consts::FRAC_PI_2);
    let pose = |t: f32| asset.rig.instance_matrices(t);
    let still = Mat4::from_translation(Vec3::new(-5.0, 0.0, 0.0));
    for (t, want) in [
        (-1.0, Mat4::IDENTITY),
        (0.0, Mat4::IDENTITY),
        (0.25, Mat4::from_translation(Vec3::new(0.5, 0.0, 0.0))),
        (0.75, Mat4::from_scale_rotation_translation(Vec3::ONE, quarter, Vec3::new(1.5, 0.0, 0.0))),
        // Zero tangents: the spline's middle is the keys' mean.
        (1.5, Mat4::from_scale_rotation_translation(Vec3::splat(2.0), quarter, Vec3::new(2.0, 0.0, 0.0))),
        (9.0, Mat4::from_scale_rotation_translation(Vec3::splat(3.0), quarter, Vec3::new(2.0, 0.0, 0.0))),
    ] {
        let got = pose(t);
        assert!(close(got[0], still), "the still node moved at {t}: {:?}", got[0]);
        assert!(close(got[1], want), "at {t} s: {:?} where {want:?} was due", got[1]);
    }
}

#[test]
fn posing_sets_the_moving_instances_transform_in_the_context() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("rt-scene-animation");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("moving.glb");
    std::fs::write(&path, moving().to_glb()).unwrap();
    let mut ctx = Context::new();
    let loaded = rt_scene::load(&mut ctx, &path).unwrap();
    let animation = loaded.animation.as_ref().expect("the file is animated");
    assert_eq!((animation.start, animation.end), (0.0, 2.0));
    animation.pose(&mut ctx, 0.25).unwrap();
    assert!(close(animation.instance_matrices(0.25)[1], Mat4::from_translation(Vec3::new(0.5, 0.0, 0.0))));
    // A file without animations has none to pose.
    let mut still = GltfBuilder::new();
    let mesh = still.mesh("tri", &triangle(), &[]);
    still.node(mesh, Mat4::IDENTITY);
    std::fs::write(dir.join("still.glb"), still.to_glb()).unwrap();
    assert!(rt_scene::load(&mut ctx, &dir.join("still.glb")).unwrap().animation.is_none());
}

fn refused(b: &GltfBuilder) -> String {
    rt_scene::gltf::parse(&b.to_glb(), "bad.glb", None).unwrap_err().to_string()
}

#[test]
fn bad_channels_are_refused_by_name() {
    let one = |target: &str, interpolation: &str, times: &[f32], values: &[Vec4]| {
        let mut b = GltfBuilder::new();
        let mesh = b.mesh("tri", &triangle(), &[]);
        let node = b.trs_node(mesh, Vec3::ZERO, Quat::IDENTITY, Vec3::ONE);
        b.animate(node, target, interpolation, times, values);
        refused(&b)
    };
    let v = Vec4::ZERO;
    assert_eq!(
        one("translation", "LINEAR", &[1.0, 0.5], &[v, v]),
        "bad.glb: animations[0].channels[0]: key times must increase: key 1 at 0.5 follows 1"
    );
    assert_eq!(
        one("translation", "LINEAR", &[0.0, f32::NAN], &[v, v]),
        "bad.glb: animations[0].channels[0]: key 1 has time NaN, which is not finite"
    );
    assert_eq!(
        one("scale", "CUBICSPLINE", &[0.0, 1.0], &[v, v]),
        "bad.glb: animations[0].channels[0]: 2 output values for 2 keys; CubicSpline interpolation needs 6"
    );
    assert_eq!(
        one("translation", "LINEAR", &[0.0, 1.0], &[v, Vec4::new(f32::INFINITY, 0.0, 0.0, 0.0)]),
        "bad.glb: animations[0].channels[0]: output value 1 is not finite: Vec4(inf, 0.0, 0.0, 0.0)"
    );
    // An animated node must not have a matrix.
    let mut b = GltfBuilder::new();
    let mesh = b.mesh("tri", &triangle(), &[]);
    let node = b.node(mesh, Mat4::IDENTITY);
    b.animate(node, "translation", "LINEAR", &[0.0], &[v]);
    assert_eq!(
        refused(&b),
        "bad.glb: animations[0].channels[0]: it moves nodes[0], which has a matrix (animated nodes take translation, rotation and scale)"
    );
}

#[test]
fn a_flat_load_at_a_time_bakes_the_pose_and_refuses_what_it_cannot_pose() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("rt-scene-animation-flat");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("moving.glb");
    std::fs::write(&path, moving().to_glb()).unwrap();
    let limits = rt_scene::LoadLimits::default();
    let (rest, _) = rt_scene::load_flat_with(&path, &limits).unwrap();
    let (posed, _) = rt_scene::load_flat_at(&path, &limits, 0.25).unwrap();
    // The still node's triangle first, then the moving one's, 0.5 along x.
    assert_eq!(rest.mesh.positions[3..], [Vec3::ZERO, Vec3::X, Vec3::Y]);
    let moved = [Vec3::new(0.5, 0.0, 0.0), Vec3::new(1.5, 0.0, 0.0), Vec3::new(0.5, 1.0, 0.0)];
    assert!(
        posed.mesh.positions[3..].iter().zip(moved).all(|(p, q)| p.abs_diff_eq(q, 1e-6)),
        "{:?}",
        posed.mesh.positions
    );
    assert_eq!(posed.mesh.positions[..3], rest.mesh.positions[..3]);
    assert!(posed.max.x >= 1.5 - 1e-6);

    let e = rt_scene::load_flat_at(&path, &limits, f32::NAN).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("{}: cannot pose the animation at time NaN: not a finite number of seconds", path.display())
    );
    assert!(e.is_bad_input());
    let mut still = GltfBuilder::new();
    let mesh = still.mesh("tri", &triangle(), &[]);
    still.node(mesh, Mat4::IDENTITY);
    let still_path = dir.join("still.glb");
    std::fs::write(&still_path, still.to_glb()).unwrap();
    let obj = dir.join("tri.obj");
    std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    for file in [&still_path, &obj] {
        let e = rt_scene::load_flat_at(file, &limits, 1.0).unwrap_err();
        assert_eq!(e.to_string(), format!("{}: has no node animation to pose", file.display()));
    }
}
