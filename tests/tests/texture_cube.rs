//! Cube maps (`SamplerCube::sample_dir`, OptiX's cube-map textures):
//! directions into each of the six faces read that face's texels at the
//! coordinates of Vulkan's face-selection table, with exact values on
//! every target: face centres, off-centre directions (each face's `s` and
//! `t` axes), ties between axes (z, then y, then x), the zero and
//! non-finite directions, and linear filtering inside a face and clamped
//! at its edge; the host's check names the sampler and the face.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

/// Launch index `i` samples direction `dirs[i]`; the last slot gets the
/// face size.
#[rt_program(ray_generation)]
pub fn read_cube(#[var] sky: SamplerCube, #[var] dirs: Buffer<Vec3>, #[var] mut out: RwBuffer<Vec4>) {
    let i = launch_index().x;
    out[i] = sky.sample_dir(dirs[i]);
    if i == 0 {
        out[dirs.len()] = Vec4::splat(sky.size() as f32);
    }
}

/// Face `f`'s texel `(x, y)` of a 4x4 face: `100 f + 4 y + x` (and alpha 1).
fn value(f: u32, x: u32, y: u32) -> Vec4 {
    let v = (100 * f + 4 * y + x) as f32;
    Vec4::new(v, v, -v, 1.0)
}

fn faces() -> [Vec<Vec4>; 6] {
    std::array::from_fn(|f| (0..16).map(|i| value(f as u32, i % 4, i / 4)).collect())
}

fn run(on: On, filter: FilterMode, dirs: &[Vec3]) -> Vec<Vec4> {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    let sky = ctx.create_sampler_cube(faces(), 4, filter).unwrap();
    let d = ctx.create_buffer(BufferType::Input, dirs.to_vec());
    let out = ctx.create_buffer(BufferType::Output, vec![Vec4::splat(-9.0); dirs.len() + 1]);
    ctx.set_var(Scope::Context, "sky", sky).unwrap();
    ctx.set_var(Scope::Context, "dirs", d).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&read_cube::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch_1d(0, dirs.len() as u32).unwrap();
    assert!(report.exceptions.is_empty(), "{on:?}: {:?}", report.exceptions);
    ctx.read_buffer(out).unwrap()
}

#[test]
fn nearest_selects_faces_as_vulkan_does_on_every_target() {
    let v = value;
    // (direction, face, texel): s = 0.5 sc / |rc| + 0.5, texel floor(4 s).
    let cases = [
        // +x: sc = -rz, tc = -ry. s = 0.5 * 0.5 + 0.5 = 0.75 -> 3; t = 0.25 -> 1.
        (Vec3::new(2.0, 1.0, -1.0), v(0, 3, 1)),
        // -x: sc = +rz, tc = -ry. s = 0.25 -> 1, t = 0.875 -> 3.
        (Vec3::new(-4.0, -3.0, -2.0), v(1, 1, 3)),
        // +y: sc = +rx, tc = +rz. s = 0.125 -> 0, t = 0.625 -> 2.
        (Vec3::new(-3.0, 4.0, 1.0), v(2, 0, 2)),
        // -y: sc = +rx, tc = -rz. s = 0.875 -> 3, t = 0.125 -> 0.
        (Vec3::new(3.0, -4.0, 3.0), v(3, 3, 0)),
        // +z: sc = +rx, tc = -ry. s = 0.375 -> 1, t = 0.375 -> 1.
        (Vec3::new(-0.5, 0.5, 2.0), v(4, 1, 1)),
        // -z: sc = -rx, tc = -ry. s = 0.375 -> 1, t = 0.875 -> 3.
        (Vec3::new(0.5, -1.5, -2.0), v(5, 1, 3)),
        // Ties: |x| = |y| = |z| is +z or -z, |x| = |y| > |z| is y.
        (Vec3::new(1.0, 1.0, -1.0), v(5, 0, 0)),
        (Vec3::new(-1.0, -1.0, 0.5), v(3, 0, 1)),
        // The zero direction and non-finite components: face +z's centre.
        (Vec3::ZERO, v(4, 2, 2)),
        (Vec3::new(f32::NAN, f32::INFINITY, 0.0), v(4, 2, 2)),
        // Just inside a face's edge (s = 1 - 2^-24): the last texel.
        (Vec3::new(1.0, 0.0, -1.0 + f32::EPSILON), v(0, 3, 2)),
    ];
    let dirs: Vec<Vec3> = cases.iter().map(|c| c.0).collect();
    let mut want: Vec<Vec4> = cases.iter().map(|c| c.1).collect();
    want.push(Vec4::splat(4.0));
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        assert_eq!(run(on, FilterMode::Nearest, &dirs), want, "on {}", on.name());
    }
}

#[test]
fn linear_filters_within_a_face_on_every_target() {
    let v = value;
    let mean = |vs: [Vec4; 4]| (vs[0] + vs[1] + vs[2] + vs[3]) * 0.25;
    let dirs = [
        // A face's centre: the four texels around it.
        Vec3::Y,
        // +z at s = t = 0.375: texel (1, 1)'s centre exactly.
        Vec3::new(-0.25, 0.25, 1.0),
        // +x at s = t = 0.9375, a quarter texel past texel (3, 3)'s centre
        // towards the corner: its neighbours are clamped to itself.
        Vec3::new(1.0, -0.875, -0.875),
    ];
    let want = [mean([v(2, 1, 1), v(2, 2, 1), v(2, 1, 2), v(2, 2, 2)]), v(4, 1, 1), v(0, 3, 3), Vec4::splat(4.0)];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        assert_eq!(run(on, FilterMode::Linear, &dirs), want, "on {}", on.name());
    }
}

#[test]
fn faces_of_the_wrong_size_are_refused_naming_the_sampler_and_face() {
    let mut ctx = Context::new();
    let mut f = faces();
    f[3].pop();
    let e = ctx.create_sampler_cube(f, 4, FilterMode::Linear).unwrap_err().to_string();
    assert_eq!(e, "sampler 0: cube face -y has 15 texels for a 4x4 face");
    let e = ctx.create_sampler_cube(std::array::from_fn(|_| Vec::new()), 0, FilterMode::Linear).unwrap_err();
    assert_eq!(e.to_string(), "sampler 0: cube face +x has 0 texels for a 0x0 face");
    // A cube map given to a Sampler2d variable is refused at launch.
    let cube = ctx.create_sampler_cube(faces(), 4, FilterMode::Linear).unwrap();
    ctx.set_ray_type_count(0);
    ctx.set_var(Scope::Context, "sky", cube).unwrap();
    let d = ctx.create_buffer(BufferType::Input, vec![Vec3::X]);
    let out = ctx.create_buffer(BufferType::Output, vec![Vec4::ZERO; 2]);
    ctx.set_var(Scope::Context, "dirs", d).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&read_cube::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    ctx.launch_1d(0, 1).unwrap();
    let flat = ctx.create_sampler(vec![Vec4::ONE], 1, 1, WrapMode::Clamp, FilterMode::Linear).unwrap();
    ctx.set_var(Scope::Context, "sky", flat).unwrap();
    let e = ctx.launch_1d(0, 1).unwrap_err().to_string();
    assert!(e.contains("`sky`") && e.contains("SamplerCube") && e.contains("Sampler2d (SamplerId(1))"), "{e}");
}
