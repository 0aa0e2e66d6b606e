//! Mipmapped samplers (OptiX `tex2DLod`, `tex2DGrad` and mip levels):
//! `Sampler2d::sample_lod` and `sample_grad` over levels of distinct
//! constant colours, with exact values on every target: integer LODs read
//! their level, fractional ones blend two (linear mip filter) or round to
//! the nearest (a half rounding down), LODs past the last level, below 0,
//! infinite or NaN clamp; footprints of 1, 2, 4 and 8 texels are levels 0
//! to 3; host-generated mips of a checkerboard average to grey; the host's
//! checks of supplied levels name the sampler and the level.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

/// Launch index `i < lods.len()` samples at LOD `lods[i]`; the next ones
/// with the footprints `grads[j].xy()`, `grads[j].zw()`; index 0 also
/// writes the level count and `sample`'s value (level 0) past the end.
#[rt_program(ray_generation)]
pub fn mip_reads(
    #[var] tex: Sampler2d,
    #[var] uv: Vec2,
    #[var] lods: Buffer<f32>,
    #[var] grads: Buffer<Vec4>,
    #[var] mut out: RwBuffer<Vec4>,
) {
    let i = launch_index().x;
    let n = lods.len();
    if i < n {
        out[i] = tex.sample_lod(uv, lods[i]);
    } else if i < n + grads.len() {
        let g = grads[i - n];
        out[i] = tex.sample_grad(uv, g.xy(), g.zw());
    } else {
        out[i] = tex.sample(uv) + Vec4::splat(tex.levels() as f32 * 1000.0);
    }
}

/// Level `l`'s colour: small integers, so that every blend the tests make
/// is exact in f32.
fn colour(l: u32) -> Vec4 {
    let l = l as f32;
    Vec4::new(1.0 + 8.0 * l, 2.0 * l, 16.0 - 4.0 * l, 1.0)
}

/// An 8x4 texture of 4 levels (8x4, 4x2, 2x1, 1x1), each one colour.
fn constant_levels() -> Vec<Vec<Vec4>> {
    (0..4).map(|l| vec![colour(l); (8usize >> l) * (4usize >> l).max(1)]).collect()
}

const LODS: [f32; 12] = [0.0, 1.0, 2.0, 3.0, 0.5, 1.25, 2.75, 7.0, -1.0, f32::INFINITY, f32::NEG_INFINITY, f32::NAN];

/// Footprints (dx, dy) in normalised coordinates of an 8x4 texture: one
/// texel is 1/8 in u and 1/4 in v.
fn footprints() -> Vec<Vec4> {
    vec![
        Vec4::new(0.125, 0.0, 0.0, 0.0),    // 1 texel: level 0
        Vec4::new(0.25, 0.0, 0.0, 0.25),    // 2 texels along u, 1 along v: level 1
        Vec4::new(0.0, 0.0, 0.0, 1.0),      // 4 texels along v: level 2
        Vec4::new(0.0, 0.0, 1.0, 0.0),      // 8 texels along u (as dy): level 3
        Vec4::new(0.0, 0.0, 0.0, 0.0),      // no footprint: level 0
        Vec4::new(f32::NAN, 0.0, 0.0, 0.5), // a NaN side counts as 0: 2 texels, level 1
    ]
}

fn run(on: On, sampler: impl FnOnce(&mut Context) -> SamplerId, uv: Vec2) -> Vec<Vec4> {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    let tex = sampler(&mut ctx);
    let lods = ctx.create_buffer(BufferType::Input, LODS.to_vec());
    let grads = ctx.create_buffer(BufferType::Input, footprints());
    let n = LODS.len() + footprints().len() + 1;
    let out = ctx.create_buffer(BufferType::Output, vec![Vec4::splat(-1.0); n]);
    ctx.set_var(Scope::Context, "tex", tex).unwrap();
    ctx.set_var(Scope::Context, "uv", uv).unwrap();
    ctx.set_var(Scope::Context, "lods", lods).unwrap();
    ctx.set_var(Scope::Context, "grads", grads).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&mip_reads::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch_1d(0, n as u32).unwrap();
    assert!(report.exceptions.is_empty(), "{on:?}: {:?}", report.exceptions);
    ctx.read_buffer(out).unwrap()
}

fn mix(a: Vec4, b: Vec4, t: f32) -> Vec4 {
    a * (1.0 - t) + b * t
}

#[test]
fn sample_lod_and_sample_grad_read_the_levels_on_every_target() {
    let c = colour;
    let linear = [
        c(0),
        c(1),
        c(2),
        c(3),
        mix(c(0), c(1), 0.5),
        mix(c(1), c(2), 0.25),
        mix(c(2), c(3), 0.75),
        c(3),
        c(0),
        c(3),
        c(0),
        c(0),
    ];
    // Nearest: 0.5 rounds down to 0, 1.25 to 1, 2.75 up to 3.
    let nearest = [c(0), c(1), c(2), c(3), c(0), c(1), c(3), c(3), c(0), c(3), c(0), c(0)];
    let by_grad = [c(0), c(1), c(2), c(3), c(0), c(1)];
    for (mip, by_lod) in [(MipFilter::Linear, linear), (MipFilter::Nearest, nearest)] {
        for (filter, uv) in [(FilterMode::Linear, Vec2::splat(0.5)), (FilterMode::Nearest, Vec2::new(0.3, 0.7))] {
            let mut want: Vec<Vec4> = by_lod.to_vec();
            want.extend(by_grad);
            want.push(c(0) + Vec4::splat(4000.0));
            for on in On::ALL.into_iter().filter(|on| on.available()) {
                let got = run(
                    on,
                    |ctx| ctx.create_sampler_mipmapped(constant_levels(), 8, 4, WrapMode::Repeat, filter, mip).unwrap(),
                    uv,
                );
                assert_eq!(got, want, "{} {mip:?} {filter:?}", on.name());
            }
        }
    }
}

#[test]
fn generated_mips_of_a_checkerboard_are_grey() {
    // 4x4 black and white squares of one texel: every 2x2 box is half white.
    let board: Vec<Vec4> = (0..16).map(|i| Vec4::splat(((i % 4 + i / 4) % 2) as f32)).collect();
    let levels = generate_mip_levels(&board, 4, 4);
    assert_eq!(levels.len(), 3);
    assert_eq!(levels[0], board);
    assert_eq!(levels[1], vec![Vec4::splat(0.5); 4]);
    assert_eq!(levels[2], vec![Vec4::splat(0.5)]);
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let got = run(
            on,
            |ctx| {
                ctx.create_sampler_with_mips(
                    board.clone(),
                    4,
                    4,
                    WrapMode::Clamp,
                    FilterMode::Nearest,
                    MipFilter::Linear,
                )
                .unwrap()
            },
            // The centre of texel (1, 2): white at level 0.
            Vec2::new(0.375, 0.625),
        );
        let grey = Vec4::splat(0.5);
        // LODs 0, 1, 2, 3 (clamped to 2), 0.5: half way from white to grey.
        assert_eq!(got[..5], [Vec4::ONE, grey, grey, grey, Vec4::splat(0.75)], "{}", on.name());
        assert_eq!(*got.last().unwrap(), Vec4::ONE + Vec4::splat(3000.0), "{}", on.name());
    }
}

#[test]
fn generated_mips_of_odd_sizes() {
    // 5x3: level 1 is 2x1 (the last column and row left out), level 2 1x1.
    let texels: Vec<Vec4> = (0..15).map(|i| Vec4::splat(i as f32)).collect();
    let levels = generate_mip_levels(&texels, 5, 3);
    assert_eq!(levels.len(), 3);
    // (0 + 1 + 5 + 6) / 4 and (2 + 3 + 7 + 8) / 4.
    assert_eq!(levels[1], vec![Vec4::splat(3.0), Vec4::splat(5.0)]);
    assert_eq!(levels[2], vec![Vec4::splat(4.0)]);
    // A single row: an axis of one texel averages it with itself.
    let row = generate_mip_levels(&[Vec4::ONE, Vec4::splat(3.0)], 2, 1);
    assert_eq!(row, vec![vec![Vec4::ONE, Vec4::splat(3.0)], vec![Vec4::splat(2.0)]]);
    assert!(generate_mip_levels(&[Vec4::ONE], 2, 2).is_empty());
}

#[test]
fn supplied_levels_are_checked_naming_the_sampler() {
    let mut ctx = Context::new();
    let (w, f, m) = (WrapMode::Repeat, FilterMode::Linear, MipFilter::Linear);
    ctx.create_sampler(vec![Vec4::ONE], 1, 1, w, f).unwrap();
    let mut levels = constant_levels();
    levels[2].push(Vec4::ONE);
    let e = ctx.create_sampler_mipmapped(levels, 8, 4, w, f, m).unwrap_err().to_string();
    assert_eq!(e, "sampler 1: mip level 2 has 3 texels; level 2 of a 8x4 texture is 2x1 (2 texels)");
    let mut levels = constant_levels();
    levels.push(vec![Vec4::ONE]);
    let e = ctx.create_sampler_mipmapped(levels, 8, 4, w, f, m).unwrap_err().to_string();
    assert_eq!(e, "sampler 1: 5 mip levels for a 8x4 texture, whose full chain has 4 (down to 1x1)");
    let e = ctx.create_sampler_mipmapped(Vec::new(), 8, 4, w, f, m).unwrap_err().to_string();
    assert_eq!(e, "sampler 1: no mip levels for a 8x4 texture (level 0 is needed)");
    let e = ctx.create_sampler_mipmapped(vec![Vec::new()], 0, 0, w, f, m).unwrap_err().to_string();
    assert_eq!(e, "sampler 1: 1 mip levels for a 0x0 texture, whose full chain has 0 (down to 1x1)");
    let e = ctx.create_sampler_with_mips(vec![Vec4::ONE; 3], 2, 2, w, f, m).unwrap_err().to_string();
    assert_eq!(e, "sampler 1: 3 texels for a 2x2 texture");
}

#[test]
fn a_partial_chain_clamps_to_its_last_level() {
    let two = || constant_levels()[..2].to_vec();
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let s = |ctx: &mut Context| {
            ctx.create_sampler_mipmapped(two(), 8, 4, WrapMode::Mirror, FilterMode::Linear, MipFilter::Linear).unwrap()
        };
        let got = run(on, s, Vec2::splat(0.5));
        let (c0, c1) = (colour(0), colour(1));
        assert_eq!(got[..8], [c0, c1, c1, c1, mix(c0, c1, 0.5), c1, c1, c1], "{}", on.name());
        assert_eq!(*got.last().unwrap(), c0 + Vec4::splat(2000.0), "{}", on.name());
    }
}
