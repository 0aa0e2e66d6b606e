//! 3D textures (`Sampler3d`, OptiX `rtTextureSampler<float4, 3>` and
//! `tex3D`): a 4x2x2 texture read through `fetch`, `sample` with the
//! nearest filter at texel centres and across the faces for each wrap mode,
//! and trilinear `sample` blending eight texels, with exact values on every
//! target; `size`; a 2D sampler given to a `Sampler3d` variable (and the
//! other way round) is refused naming the program, variable and both types.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

/// Launch index `i` samples at `points[i]` and fetches `texels[i]`; index 0
/// also writes the size.
#[rt_program(ray_generation)]
pub fn read_volume(
    #[var] volume: Sampler3d,
    #[var] points: Buffer<Vec3>,
    #[var] texels: Buffer<UVec3>,
    #[var] mut out: RwBuffer<Vec4>,
) {
    let i = launch_index().x;
    out[i * 2] = volume.sample(points[i]);
    out[i * 2 + 1] = volume.fetch(texels[i]);
    if i == 0 {
        out[points.len() * 2] = volume.size().as_vec3().extend(0.0);
    }
}

/// Reads a 2D sampler, for the mismatch test.
#[rt_program(ray_generation)]
pub fn read_flat(#[var] volume: Sampler2d, #[var] mut out: RwBuffer<Vec4>) {
    out[0] = volume.sample(vec2(0.5, 0.5));
}

const SIZE: UVec3 = UVec3::new(4, 2, 2);

/// Texel `(x, y, z)`'s value: `x + 4y + 8z` in every channel but alpha.
fn value(x: u32, y: u32, z: u32) -> Vec4 {
    let v = (x + 4 * y + 8 * z) as f32;
    Vec4::new(v, -v, 2.0 * v, 1.0)
}

fn texels() -> Vec<Vec4> {
    (0..16).map(|i| value(i % 4, (i / 4) % 2, i / 8)).collect()
}

fn run(on: On, wrap: WrapMode, filter: FilterMode, points: &[Vec3], fetches: &[UVec3]) -> Vec<Vec4> {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    let tex = ctx.create_sampler_3d(texels(), SIZE, wrap, filter).unwrap();
    let p = ctx.create_buffer(BufferType::Input, points.to_vec());
    let t = ctx.create_buffer(BufferType::Input, fetches.to_vec());
    let out = ctx.create_buffer(BufferType::Output, vec![Vec4::splat(-9.0); points.len() * 2 + 1]);
    ctx.set_var(Scope::Context, "volume", tex).unwrap();
    ctx.set_var(Scope::Context, "points", p).unwrap();
    ctx.set_var(Scope::Context, "texels", t).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&read_volume::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch_1d(0, points.len() as u32).unwrap();
    assert!(report.exceptions.is_empty(), "{on:?}: {:?}", report.exceptions);
    ctx.read_buffer(out).unwrap()
}

/// The centre of texel (x, y, z) in normalised coordinates.
fn centre(x: f32, y: f32, z: f32) -> Vec3 {
    (Vec3::new(x, y, z) + 0.5) / SIZE.as_vec3()
}

#[test]
fn nearest_reads_texels_and_wraps_per_mode_on_every_target() {
    let points = [
        centre(1.0, 0.0, 1.0),
        centre(3.0, 1.0, 0.0),
        // Past each face: texel -1 in x, 2 in y, 2 in z.
        centre(-1.0, 0.0, 0.0),
        centre(2.0, 2.0, 1.0),
        centre(0.0, 1.0, 2.0),
        Vec3::new(f32::NAN, 0.75, 0.75),
    ];
    let fetches = [UVec3::new(1, 0, 1), UVec3::new(3, 1, 0), UVec3::new(9, 9, 9), UVec3::ZERO, UVec3::Z, UVec3::X];
    let v = value;
    for (wrap, wrapped) in [
        (WrapMode::Repeat, [v(3, 0, 0), v(2, 0, 1), v(0, 1, 0)]),
        (WrapMode::Clamp, [v(0, 0, 0), v(2, 1, 1), v(0, 1, 1)]),
        (WrapMode::Mirror, [v(0, 0, 0), v(2, 1, 1), v(0, 1, 1)]),
    ] {
        let want = [
            v(1, 0, 1),
            v(1, 0, 1),
            v(3, 1, 0),
            v(3, 1, 0),
            wrapped[0],
            v(3, 1, 1),
            wrapped[1],
            v(0, 0, 0),
            wrapped[2],
            v(0, 0, 1),
            v(0, 1, 1),
            v(1, 0, 0),
            SIZE.as_vec3().extend(0.0),
        ];
        for on in On::ALL.into_iter().filter(|on| on.available()) {
            let got = run(on, wrap, FilterMode::Nearest, &points, &fetches);
            assert_eq!(got, want, "{wrap:?} on {}", on.name());
        }
    }
}

#[test]
fn linear_blends_eight_texels_on_every_target() {
    let v = value;
    let mean = |vs: &[Vec4]| vs.iter().copied().sum::<Vec4>() / vs.len() as f32;
    // At the corner shared by texels x 1..2, y 0..1, z 0..1: the mean of all
    // eight; half way between two centres along one axis: their mean; at a
    // centre: that texel.
    let points = [Vec3::new(0.5, 0.5, 0.5), centre(1.5, 0.0, 1.0), centre(2.0, 1.0, 0.5), centre(3.0, 0.0, 1.0)];
    let want_clamp = [
        mean(&[v(1, 0, 0), v(2, 0, 0), v(1, 1, 0), v(2, 1, 0), v(1, 0, 1), v(2, 0, 1), v(1, 1, 1), v(2, 1, 1)]),
        mean(&[v(1, 0, 1), v(2, 0, 1)]),
        mean(&[v(2, 1, 0), v(2, 1, 1)]),
        v(3, 0, 1),
    ];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let got = run(on, WrapMode::Clamp, FilterMode::Linear, &points, &[UVec3::ZERO; 4]);
        let sampled: Vec<Vec4> = got.iter().step_by(2).take(4).copied().collect();
        assert_eq!(sampled, want_clamp, "on {}", on.name());
    }
    // At uvw = 0 with repeat: the eight corner texels, x 3 and 0, y 1 and 0,
    // z 1 and 0, each a quarter texel away.
    let corner =
        mean(&[v(3, 1, 1), v(0, 1, 1), v(3, 0, 1), v(0, 0, 1), v(3, 1, 0), v(0, 1, 0), v(3, 0, 0), v(0, 0, 0)]);
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let got = run(on, WrapMode::Repeat, FilterMode::Linear, &[Vec3::ZERO], &[UVec3::ZERO]);
        assert_eq!(got[0], corner, "repeat at the corner on {}", on.name());
    }
}

#[test]
fn sampler_dimensions_must_match_the_variable() {
    for on in [On::CPU, On::COMPUTE] {
        let mut ctx = on.context();
        ctx.set_ray_type_count(0);
        let flat = ctx.create_sampler(vec![Vec4::ONE], 1, 1, WrapMode::Clamp, FilterMode::Linear).unwrap();
        let out = ctx.create_buffer(BufferType::Output, vec![Vec4::ZERO; 3]);
        ctx.set_var(Scope::Context, "out", out).unwrap();
        ctx.set_var(Scope::Context, "volume", flat).unwrap();
        let points = ctx.create_buffer(BufferType::Input, vec![Vec3::ZERO]);
        let texels = ctx.create_buffer(BufferType::Input, vec![UVec3::ZERO]);
        ctx.set_var(Scope::Context, "points", points).unwrap();
        ctx.set_var(Scope::Context, "texels", texels).unwrap();
        let rg = ctx.create_program(&read_volume::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let e = ctx.launch_1d(0, 1).unwrap_err().to_string();
        assert!(e.contains("`volume`") && e.contains("Sampler3d") && e.contains("Sampler2d (SamplerId(0))"), "{e}");
        // And a 3D sampler where a 2D one is read.
        let cube = ctx.create_sampler_3d(vec![Vec4::ONE; 8], UVec3::splat(2), WrapMode::Clamp, FilterMode::Linear);
        let cube = cube.unwrap();
        ctx.set_var(Scope::Context, "volume", cube).unwrap();
        let flat_rg = ctx.create_program(&read_flat::PROGRAM);
        ctx.set_ray_generation_program(0, flat_rg).unwrap();
        let e = ctx.launch_1d(0, 1).unwrap_err().to_string();
        assert!(e.contains("read_flat") && e.contains("Sampler3d (SamplerId(1))"), "{e}");
        // A sampler where a buffer is read: named by its own shape.
        ctx.set_ray_generation_program(0, rg).unwrap();
        ctx.set_var(Scope::Context, "points", cube).unwrap();
        let e = ctx.launch_1d(0, 1).unwrap_err().to_string();
        assert!(e.contains("`points`") && e.contains("sets it to `Sampler3d`"), "{e}");
    }
    let mut ctx = Context::new();
    let e = ctx.create_sampler_3d(vec![Vec4::ONE; 7], UVec3::splat(2), WrapMode::Clamp, FilterMode::Linear);
    assert_eq!(e.unwrap_err().to_string(), "sampler 0: 7 texels for a 2x2x2 texture");
}
