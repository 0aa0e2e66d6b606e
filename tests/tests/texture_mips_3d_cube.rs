//! Mip levels of 3D textures and cube maps (OptiX `tex3DLod`,
//! `tex3DGrad`, `texCubemapLod`): `Sampler3d::sample_lod`, `sample_grad`
//! (the level of a footprint) and
//! `SamplerCube::sample_dir_lod` over levels of distinct constant colours,
//! read through a variable and through a bindless id, with exact values on
//! every target: integer LODs read their level, fractional ones blend two
//! (linear mip filter) or round to the nearest (a half rounding down), LODs
//! past the last level, below 0, infinite or NaN clamp; host-generated
//! levels (a 2x2x2 box filter in 3D, 2x2 within each cube face) of a
//! checkerboard are grey; the host's checks of supplied levels name the
//! sampler, the level and the face.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

/// Launch index `i` samples at LOD `lods[i]` through the variable and the
/// id; index 0 also writes the level counts and `sample`'s value (level 0)
/// past the end.
#[rt_program(ray_generation)]
pub fn volume_lods(
    #[var] volume: Sampler3d,
    #[var] by_id: BindlessSampler<Sampler3d>,
    #[var] uvw: Vec3,
    #[var] lods: Buffer<f32>,
    #[var] mut out: RwBuffer<Vec4>,
) {
    let i = launch_index().x;
    out[i * 2] = volume.sample_lod(uvw, lods[i]);
    out[i * 2 + 1] = by_id.sample_lod(uvw, lods[i]);
    if i == 0 {
        out[lods.len() * 2] = vec4(volume.levels() as f32, by_id.levels() as f32, volume.sample(uvw).x, 0.0);
    }
}

/// Launch index `i` samples at the footprint `grads[2 i]`, `grads[2 i + 1]`
/// (their xyz) through the variable and the id.
#[rt_program(ray_generation)]
pub fn volume_grads(
    #[var] volume: Sampler3d,
    #[var] by_id: BindlessSampler<Sampler3d>,
    #[var] grads: Buffer<Vec4>,
    #[var] mut out: RwBuffer<Vec4>,
) {
    let i = launch_index().x;
    let (dx, dy) = (grads[i * 2].xyz(), grads[i * 2 + 1].xyz());
    out[i * 2] = volume.sample_grad(vec3(0.5, 0.5, 0.5), dx, dy);
    out[i * 2 + 1] = by_id.sample_grad(vec3(0.5, 0.5, 0.5), dx, dy);
}

/// As `volume_lods`, for a cube map in direction `dir`.
#[rt_program(ray_generation)]
pub fn cube_lods(
    #[var] cube: SamplerCube,
    #[var] by_id: BindlessSampler<SamplerCube>,
    #[var] dir: Vec3,
    #[var] lods: Buffer<f32>,
    #[var] mut out: RwBuffer<Vec4>,
) {
    let i = launch_index().x;
    out[i * 2] = cube.sample_dir_lod(dir, lods[i]);
    out[i * 2 + 1] = by_id.sample_dir_lod(dir, lods[i]);
    if i == 0 {
        out[lods.len() * 2] = vec4(cube.levels() as f32, by_id.levels() as f32, cube.sample_dir(dir).x, 0.0);
    }
}

/// Level `l`'s colour, face `face`'s alpha: small integers, so that every
/// blend the tests make is exact in f32.
fn colour(l: u32, face: u32) -> Vec4 {
    let l = l as f32;
    Vec4::new(1.0 + 8.0 * l, 2.0 * l, 16.0 - 4.0 * l, 1.0 + face as f32)
}

const LODS: [f32; 11] = [0.0, 1.0, 2.0, 0.5, 1.25, 1.75, 7.0, -1.0, f32::INFINITY, f32::NEG_INFINITY, f32::NAN];

/// What LODS read from three levels of colours `c(l)`, by mip filter.
fn want(mip: MipFilter, c: impl Fn(u32) -> Vec4) -> Vec<Vec4> {
    let mix = |a: Vec4, b: Vec4, t: f32| a * (1.0 - t) + b * t;
    match mip {
        MipFilter::Linear => vec![
            c(0),
            c(1),
            c(2),
            mix(c(0), c(1), 0.5),
            mix(c(1), c(2), 0.25),
            mix(c(1), c(2), 0.75),
            c(2),
            c(0),
            c(2),
            c(0),
            c(0),
        ],
        // 0.5 rounds down to 0, 1.25 to 1, 1.75 up to 2.
        MipFilter::Nearest => vec![c(0), c(1), c(2), c(0), c(1), c(2), c(2), c(0), c(2), c(0), c(0)],
    }
}

/// Runs `program` with `sampler` as its variable and id, `at` as its
/// `uvw`/`dir`: per LOD the variable's and the id's samples, then the
/// levels' line.
fn run(
    on: On,
    program: &'static rt_std::program::ProgramDescriptor,
    sampler: SamplerId,
    ctx: &mut Context,
    at: Vec3,
) -> Vec<Vec4> {
    let (var, coordinate) = if program.name == "volume_lods" { ("volume", "uvw") } else { ("cube", "dir") };
    ctx.set_ray_type_count(0);
    let lods = ctx.create_buffer(BufferType::Input, LODS.to_vec());
    let out = ctx.create_buffer(BufferType::Output, vec![Vec4::splat(-1.0); LODS.len() * 2 + 1]);
    ctx.set_var(Scope::Context, var, sampler).unwrap();
    let id = if var == "volume" {
        ctx.sampler_id::<Sampler3d>(sampler).unwrap().id()
    } else {
        ctx.sampler_id::<SamplerCube>(sampler).unwrap().id()
    };
    if var == "volume" {
        ctx.set_var(Scope::Context, "by_id", BindlessSampler::<Sampler3d>::from_id(id)).unwrap();
    } else {
        ctx.set_var(Scope::Context, "by_id", BindlessSampler::<SamplerCube>::from_id(id)).unwrap();
    }
    ctx.set_var(Scope::Context, coordinate, at).unwrap();
    ctx.set_var(Scope::Context, "lods", lods).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(program);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch_1d(0, LODS.len() as u32).unwrap();
    assert!(report.exceptions.is_empty(), "{on:?}: {:?}", report.exceptions);
    ctx.read_buffer(out).unwrap()
}

/// The variable's samples and the id's, each as they should be.
fn check(got: &[Vec4], want: &[Vec4], levels: f32, level0: f32, what: &str) {
    let n = want.len();
    let by_var: Vec<Vec4> = got[..2 * n].iter().step_by(2).copied().collect();
    let by_id: Vec<Vec4> = got[1..2 * n].iter().step_by(2).copied().collect();
    assert_eq!(by_var, want, "{what}: through the variable");
    assert_eq!(by_id, want, "{what}: through the id");
    assert_eq!(got[2 * n], Vec4::new(levels, levels, level0, 0.0), "{what}: levels and sample");
}

#[test]
fn sample_lod_reads_3d_levels_through_variables_and_ids_on_every_target() {
    // 4x2x2, 2x1x1, 1x1x1.
    let size = UVec3::new(4, 2, 2);
    let levels = || (0..3).map(|l| vec![colour(l, 0); [16, 2, 1][l as usize]]).collect::<Vec<_>>();
    for mip in [MipFilter::Linear, MipFilter::Nearest] {
        for (filter, uvw) in [(FilterMode::Linear, Vec3::splat(0.5)), (FilterMode::Nearest, Vec3::new(0.3, 0.7, 0.1))] {
            for on in On::ALL.into_iter().filter(|on| on.available()) {
                let mut ctx = on.context();
                let s = ctx.create_sampler_3d_mipmapped(levels(), size, WrapMode::Repeat, filter, mip).unwrap();
                let got = run(on, &volume_lods::PROGRAM, s, &mut ctx, uvw);
                check(&got, &want(mip, |l| colour(l, 0)), 3.0, 1.0, &format!("{} {mip:?} {filter:?}", on.name()));
            }
        }
    }
}

/// `sample_grad` (OptiX `tex3DGrad`) takes log2 of the footprint's longer
/// side in level-0 texels (of a 4x2x1 volume): each axis scaled by its own
/// size, either derivative the longer, a NaN side ignored, no footprint or
/// an infinite one clamped to the first or last level.
#[test]
fn sample_grad_reads_the_3d_level_of_the_footprint_on_every_target() {
    // 4x2x1, 2x1x1, 1x1x1: each axis its own size.
    let size = UVec3::new(4, 2, 1);
    let levels = || (0..3).map(|l| vec![colour(l, 0); [8, 2, 1][l as usize]]).collect::<Vec<_>>();
    let v = |x: f32, y: f32, z: f32| Vec4::new(x, y, z, 0.0);
    let nan = f32::NAN;
    // (dx, dy, level read)
    let cases = [
        (v(0.25, 0.0, 0.0), v(0.0, 0.0, 0.0), 0),
        (v(0.5, 0.0, 0.0), v(0.0, 0.0, 0.0), 1),
        (v(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0), 0),
        (v(0.0, 0.0, 0.0), v(0.0, 0.0, 2.0), 1),
        (v(0.0, 0.0, 4.0), v(0.0, 0.0, 0.0), 2),
        (v(0.0, 1.0, 0.0), v(0.125, 0.0, 0.0), 1),
        (v(0.125, 0.0, 0.0), v(0.0, 2.0, 0.0), 2),
        (v(nan, 0.0, 0.0), v(0.5, 0.0, 0.0), 1),
        (v(0.0, 0.0, 0.0), v(0.0, 0.0, 0.0), 0),
        (v(f32::INFINITY, 0.0, 0.0), v(0.0, 0.0, 0.0), 2),
        (v(0.0, 0.0, 8.0), v(0.0, 0.0, 0.0), 2),
    ];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        ctx.set_ray_type_count(0);
        let s = ctx
            .create_sampler_3d_mipmapped(levels(), size, WrapMode::Repeat, FilterMode::Linear, MipFilter::Linear)
            .unwrap();
        let grads = ctx.create_buffer(BufferType::Input, cases.iter().flat_map(|(dx, dy, _)| [*dx, *dy]).collect());
        let out = ctx.create_buffer(BufferType::Output, vec![Vec4::splat(-1.0); cases.len() * 2]);
        let id = ctx.sampler_id::<Sampler3d>(s).unwrap();
        ctx.set_var(Scope::Context, "volume", s).unwrap();
        ctx.set_var(Scope::Context, "by_id", id).unwrap();
        ctx.set_var(Scope::Context, "grads", grads).unwrap();
        ctx.set_var(Scope::Context, "out", out).unwrap();
        let rg = ctx.create_program(&volume_grads::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let report = ctx.launch_1d(0, cases.len() as u32).unwrap();
        assert!(report.exceptions.is_empty(), "{on:?}: {:?}", report.exceptions);
        let got: Vec<Vec4> = ctx.read_buffer(out).unwrap();
        let want: Vec<Vec4> = cases.iter().flat_map(|(_, _, l)| [colour(*l, 0); 2]).collect();
        assert_eq!(got, want, "{}", on.name());
    }
}

#[test]
fn sample_dir_lod_reads_cube_levels_through_variables_and_ids_on_every_target() {
    // Faces of 4x4, 2x2 and 1x1; face f of level l is colour(l, f).
    let levels = || -> Vec<[Vec<Vec4>; 6]> {
        (0..3).map(|l| std::array::from_fn(|f| vec![colour(l, f as u32); [16, 4, 1][l as usize]])).collect()
    };
    for mip in [MipFilter::Linear, MipFilter::Nearest] {
        for filter in [FilterMode::Linear, FilterMode::Nearest] {
            // Face -y (3), and face +x (0) off its centre.
            for (dir, face) in [(-Vec3::Y, 3), (Vec3::new(1.0, 0.3, -0.6), 0)] {
                for on in On::ALL.into_iter().filter(|on| on.available()) {
                    let mut ctx = on.context();
                    let s = ctx.create_sampler_cube_mipmapped(levels(), 4, filter, mip).unwrap();
                    let got = run(on, &cube_lods::PROGRAM, s, &mut ctx, dir);
                    let what = format!("{} {mip:?} {filter:?} face {face}", on.name());
                    check(&got, &want(mip, |l| colour(l, face)), 3.0, 1.0, &what);
                }
            }
        }
    }
}

#[test]
fn generated_levels_of_checkerboards_are_grey_on_every_target() {
    // Box filters, on the host: a 4x2x1 volume of x gives 2x1x1 of the
    // pairs' means, then their mean.
    let ramp: Vec<Vec4> = (0..8).map(|i| Vec4::splat((i % 4) as f32)).collect();
    let levels = generate_mip_levels_3d(&ramp, UVec3::new(4, 2, 1));
    assert_eq!(levels.len(), 3);
    assert_eq!(levels[1], vec![Vec4::splat(0.5), Vec4::splat(2.5)]);
    assert_eq!(levels[2], vec![Vec4::splat(1.5)]);
    assert!(generate_mip_levels_3d(&ramp, UVec3::new(4, 2, 2)).is_empty());
    // A 2x2x2 and a 2x2-faced checkerboard: level 1 is half white.
    let board3: Vec<Vec4> = (0..8).map(|i| Vec4::splat(((i % 2 + i / 2 % 2 + i / 4) % 2) as f32)).collect();
    let board2 = |f: usize| (0..4).map(|i| Vec4::splat(((i % 2 + i / 2 + f) % 2) as f32)).collect::<Vec<_>>();
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        let s = ctx
            .create_sampler_3d_with_mips(
                board3.clone(),
                UVec3::splat(2),
                WrapMode::Clamp,
                FilterMode::Nearest,
                MipFilter::Nearest,
            )
            .unwrap();
        let got = run(on, &volume_lods::PROGRAM, s, &mut ctx, Vec3::new(0.75, 0.25, 0.25));
        // LOD 0 reads texel (1, 0, 0): white; LOD 1 and past, grey.
        assert_eq!(got[0], Vec4::ONE, "{}", on.name());
        assert_eq!(got[2], Vec4::splat(0.5), "{}", on.name());
        assert_eq!(got[2 * LODS.len()], Vec4::new(2.0, 2.0, 1.0, 0.0), "{}", on.name());
        let mut ctx = on.context();
        let faces = std::array::from_fn(board2);
        let s = ctx.create_sampler_cube_with_mips(faces, 2, FilterMode::Nearest, MipFilter::Nearest).unwrap();
        let got = run(on, &cube_lods::PROGRAM, s, &mut ctx, Vec3::Z);
        // Face +z's centre at nearest is texel (1, 1): (1 + 1 + 4) % 2 = 0.
        assert_eq!(got[0], Vec4::ZERO, "{}", on.name());
        assert_eq!(got[2], Vec4::splat(0.5), "{}", on.name());
        assert_eq!(got[2 * LODS.len()], Vec4::new(2.0, 2.0, 0.0, 0.0), "{}", on.name());
    }
}

#[test]
fn supplied_levels_are_checked_naming_the_sampler_level_and_face() {
    let mut ctx = Context::new();
    let size = UVec3::new(4, 2, 2);
    let (w, f, m) = (WrapMode::Clamp, FilterMode::Nearest, MipFilter::Linear);
    let e = ctx.create_sampler_3d_mipmapped(vec![vec![Vec4::ONE; 16], vec![Vec4::ONE; 3]], size, w, f, m).unwrap_err();
    assert_eq!(e.to_string(), "sampler 0: mip level 1 has 3 texels; level 1 of a 4x2x2 texture is 2x1x1 (2 texels)");
    let four = vec![vec![Vec4::ONE; 16], vec![Vec4::ONE; 2], vec![Vec4::ONE], vec![Vec4::ONE]];
    let e = ctx.create_sampler_3d_mipmapped(four, size, w, f, m).unwrap_err().to_string();
    assert!(e.contains("4 mip levels") && e.contains("full chain has 3"), "{e}");
    let mut levels: Vec<[Vec<Vec4>; 6]> = vec![std::array::from_fn(|_| vec![Vec4::ONE; 4])];
    levels.push(std::array::from_fn(|f| vec![Vec4::ONE; if f == 4 { 2 } else { 1 }]));
    let e = ctx.create_sampler_cube_mipmapped(levels, 2, f, m).unwrap_err().to_string();
    assert_eq!(e, "sampler 0: cube face +z of mip level 1 has 2 texels for a 1x1 face");
    // Nothing was made: the next sampler is still sampler 0.
    let s = ctx.create_sampler_3d_with_mips(vec![Vec4::ONE; 16], size, w, f, m).unwrap();
    assert_eq!(ctx.sampler_id::<Sampler3d>(s).unwrap().id(), 1);
}
