//! Texel formats of samplers (`TexelData`: RGBA8 linear and sRGB, RGBA16F,
//! RGBA32F, R8, R32F) with OptiX's read modes (normalised float, element
//! type) and index modes (normalised coordinates, array index): each
//! format's texels read back on every target with exact values written out
//! here (`c / 255`, the sRGB formula's values, halves' exact values, one
//! channel as `(r, 0, 0, 1)`), through `fetch` and through `sample` at
//! texel centres in either index mode; a linear sample between two texels
//! in texel coordinates; the same formats behind 3D samplers and cube
//! maps; a 3D sampler in texel coordinates; the host's checks name the
//! sampler.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

/// Launch index `i` writes texel `i` fetched, sampled at its centre and
/// sampled at its right edge (the next texel's left edge), in normalised
/// or texel coordinates as `texel_coords` says.
#[rt_program(ray_generation)]
pub fn read_texels(#[var] tex: Sampler2d, #[var] texel_coords: u32, #[var] mut out: RwBuffer<Vec4>) {
    let i = launch_index().x;
    let n = tex.size().x as f32;
    let mut scale = 1.0 / n;
    if texel_coords == 1 {
        scale = 1.0;
    }
    out[i * 3] = tex.fetch(uvec2(i, 0));
    out[i * 3 + 1] = tex.sample(vec2((i as f32 + 0.5) * scale, 0.5));
    out[i * 3 + 2] = tex.sample(vec2((i as f32 + 1.0) * scale, 0.5));
}

fn run(on: On, data: TexelData, options: SamplerOptions) -> Vec<Vec4> {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    let n = data.len() as u32;
    let tex = ctx.create_sampler_from_texels(data, n, 1, options).unwrap();
    let out = ctx.create_buffer(BufferType::Output, vec![Vec4::splat(-7.0); 3 * n as usize]);
    ctx.set_var(Scope::Context, "tex", tex).unwrap();
    ctx.set_var(Scope::Context, "texel_coords", u32::from(options.index == IndexMode::ArrayIndex)).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&read_texels::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch_1d(0, n).unwrap();
    assert!(report.exceptions.is_empty(), "{on:?}: {:?}", report.exceptions);
    ctx.read_buffer(out).unwrap()
}

/// `128 / 255` as the nearest f32.
const C128: f32 = 0.501_960_8;
/// The sRGB formula at code 128: ((128/255 + 0.055) / 1.055)^2.4.
const SRGB128: f32 = 0.215_860_5;
/// At code 10 (below the knee): 10 / 255 / 12.92.
const SRGB10: f32 = 0.003_035_27;

fn cases() -> Vec<(&'static str, TexelData, ReadMode, Vec<Vec4>)> {
    use ReadMode::*;
    let bytes = vec![[0, 51, 128, 255], [10, 255, 0, 128]];
    vec![
        (
            "rgba8",
            TexelData::Rgba8(bytes.clone()),
            NormalizedFloat,
            vec![Vec4::new(0.0, 0.2, C128, 1.0), Vec4::new(10.0 / 255.0, 1.0, 0.0, C128)],
        ),
        (
            "rgba8 element",
            TexelData::Rgba8(bytes.clone()),
            ElementType,
            vec![Vec4::new(0.0, 51.0, 128.0, 255.0), Vec4::new(10.0, 255.0, 0.0, 128.0)],
        ),
        (
            "rgba8 srgb",
            TexelData::Rgba8Srgb(bytes.clone()),
            NormalizedFloat,
            // sRGB colour, linear alpha.
            vec![Vec4::new(0.0, 0.033_104_766, SRGB128, 1.0), Vec4::new(SRGB10, 1.0, 0.0, C128)],
        ),
        (
            "rgba8 srgb element",
            TexelData::Rgba8Srgb(bytes),
            ElementType,
            vec![Vec4::new(0.0, 51.0, 128.0, 255.0), Vec4::new(10.0, 255.0, 0.0, 128.0)],
        ),
        (
            "rgba16f",
            TexelData::Rgba16F(vec![[0x3c00, 0xc000, 0x3555, 0x7bff], [0x0001, 0x8000, 0x3800, 0x4248]]),
            NormalizedFloat,
            vec![Vec4::new(1.0, -2.0, 0.333_251_95, 65504.0), Vec4::new(5.960_464_5e-8, -0.0, 0.5, 3.140_625)],
        ),
        (
            "rgba32f",
            TexelData::Rgba32F(vec![Vec4::new(0.1, -3.5, 1e30, 0.0), Vec4::new(7.0, 0.25, -1e-30, 2.0)]),
            ElementType,
            vec![Vec4::new(0.1, -3.5, 1e30, 0.0), Vec4::new(7.0, 0.25, -1e-30, 2.0)],
        ),
        (
            "r8",
            TexelData::R8(vec![51, 255, 0]),
            NormalizedFloat,
            vec![Vec4::new(0.2, 0.0, 0.0, 1.0), Vec4::new(1.0, 0.0, 0.0, 1.0), Vec4::new(0.0, 0.0, 0.0, 1.0)],
        ),
        (
            "r8 element",
            TexelData::R8(vec![51, 255, 0]),
            ElementType,
            vec![Vec4::new(51.0, 0.0, 0.0, 1.0), Vec4::new(255.0, 0.0, 0.0, 1.0), Vec4::new(0.0, 0.0, 0.0, 1.0)],
        ),
        (
            "r32f",
            TexelData::R32F(vec![0.1, -2.5]),
            NormalizedFloat,
            vec![Vec4::new(0.1, 0.0, 0.0, 1.0), Vec4::new(-2.5, 0.0, 0.0, 1.0)],
        ),
    ]
}

#[test]
fn every_format_decodes_exactly_on_every_target() {
    for (name, data, read, want) in cases() {
        assert_eq!(data.decode(read), want, "{name}: the host's decoding");
        let n = want.len();
        for index in [IndexMode::NormalizedCoordinates, IndexMode::ArrayIndex] {
            let options = SamplerOptions { wrap: WrapMode::Clamp, filter: FilterMode::Nearest, read, index };
            for on in On::ALL.into_iter().filter(|on| on.available()) {
                let got = run(on, data.clone(), options);
                for i in 0..n {
                    let at = format!("{name} {index:?} on {}, texel {i}", on.name());
                    assert_eq!(
                        got[3 * i].to_array().map(f32::to_bits),
                        want[i].to_array().map(f32::to_bits),
                        "{at}: fetch"
                    );
                    assert_eq!(got[3 * i + 1], want[i], "{at}: sample at the centre");
                    // Nearest at the right edge: the next texel, the last
                    // one clamped.
                    assert_eq!(got[3 * i + 2], want[(i + 1).min(n - 1)], "{at}: sample at the right edge");
                }
            }
        }
    }
}

#[test]
fn linear_filtering_in_texel_coordinates_blends_the_decoded_texels() {
    // sRGB decodes before filtering, as GPUs' sRGB formats do: half way
    // between codes 0 and 128 is half of 128's linear value, not code 64's.
    // Four texels, so that normalised coordinates are exact too.
    let data = TexelData::Rgba8Srgb(vec![[0; 4], [128; 4], [255; 4], [255; 4]]);
    for index in [IndexMode::NormalizedCoordinates, IndexMode::ArrayIndex] {
        let options = SamplerOptions {
            wrap: WrapMode::Clamp,
            filter: FilterMode::Linear,
            read: ReadMode::NormalizedFloat,
            index,
        };
        for on in On::ALL.into_iter().filter(|on| on.available()) {
            let got = run(on, data.clone(), options);
            let (dark, mid, white) = (Vec4::ZERO, Vec4::new(SRGB128, SRGB128, SRGB128, C128), Vec4::ONE);
            let at = format!("{index:?} on {}", on.name());
            assert_eq!([got[1], got[4], got[7]], [dark, mid, white], "{at}: centres");
            assert_eq!(got[2], mid * 0.5, "{at}: between 0 and 128");
            assert_eq!(got[5], mid * 0.5 + white * 0.5, "{at}: between 128 and 255");
            assert_eq!(got[8], white, "{at}: between 255 and 255");
            assert_eq!(got[11], white, "{at}: clamped past the end");
        }
    }
}

#[test]
fn bad_texels_and_modes_are_refused_naming_the_sampler() {
    let mut ctx = Context::new();
    let options = SamplerOptions::default();
    let e = ctx.create_sampler_from_texels(TexelData::R8(vec![1, 2, 3]), 2, 2, options).unwrap_err().to_string();
    assert_eq!(e, "sampler 0: 3 R8 texels for a 2x2 texture");
    let e = ctx.create_sampler_from_texels(TexelData::Rgba16F(Vec::new()), 0, 0, options).unwrap_err().to_string();
    assert_eq!(e, "sampler 0: 0 Rgba16F texels for a 0x0 texture");
    let array = SamplerOptions { index: IndexMode::ArrayIndex, wrap: WrapMode::Mirror, ..options };
    let e = ctx.create_sampler_from_texels(TexelData::R32F(vec![1.0]), 1, 1, array).unwrap_err().to_string();
    assert_eq!(
        e,
        "sampler 0: array-index coordinates (RT_TEXTURE_INDEX_ARRAY_INDEX) clamp to the edge, as GPUs' unnormalised coordinates do: use WrapMode::Clamp, not Mirror"
    );
    let ok = SamplerOptions { wrap: WrapMode::Clamp, ..array };
    ctx.create_sampler_from_texels(TexelData::R32F(vec![1.0]), 1, 1, ok).unwrap();
}

/// Launch index `i` (0 to 5) fetches and samples texel `(i, 0, 0)` of the
/// volume (clamped to its width), and samples the centre of cube face `i`
/// (+x, -x, +y, -y, +z, -z).
#[rt_program(ray_generation)]
pub fn read_volume_and_cube(#[var] volume: Sampler3d, #[var] cube: SamplerCube, #[var] mut out: RwBuffer<Vec4>) {
    let i = launch_index().x;
    let n = volume.size().x as f32;
    out[i * 3] = volume.fetch(uvec3(i, 0, 0));
    out[i * 3 + 1] = volume.sample(vec3((i as f32 + 0.5) / n, 0.5, 0.5));
    let s = 1.0 - 2.0 * (i % 2) as f32;
    let mut d = vec3(0.0, 0.0, s);
    if i / 2 == 0 {
        d = vec3(s, 0.0, 0.0);
    } else if i / 2 == 1 {
        d = vec3(0.0, s, 0.0);
    }
    out[i * 3 + 2] = cube.sample_dir(d);
}

/// Launch index `i` samples the volume at `at[i]` (texel coordinates).
#[rt_program(ray_generation)]
pub fn volume_at(#[var] volume: Sampler3d, #[var] at: Buffer<Vec4>, #[var] mut out: RwBuffer<Vec4>) {
    let i = launch_index().x;
    out[i] = volume.sample(at[i].xyz());
}

/// A 4x2x2 volume of R32F texels `x + 10 y + 100 z` in array-index mode
/// (OptiX's `RT_TEXTURE_INDEX_ARRAY_INDEX`): coordinates in texels, nearest
/// at texel centres and corners, linear between centres along each axis
/// and clamped past the edges; one level (`levels()` is 1).
#[test]
fn a_3d_sampler_reads_texel_coordinates_in_array_index_mode_on_every_target() {
    let texels: Vec<f32> = (0..16).map(|i| (i % 4 + 10 * ((i / 4) % 2) + 100 * (i / 8)) as f32).collect();
    let value = |v: f32| Vec4::new(v, 0.0, 0.0, 1.0);
    let at = [
        Vec4::new(0.5, 0.5, 0.5, 0.0),
        Vec4::new(3.5, 1.5, 1.5, 0.0),
        Vec4::new(2.0, 1.0, 1.0, 0.0),
        Vec4::new(9.0, -3.0, 1.0, 0.0),
        Vec4::new(1.0, 0.5, 0.5, 0.0),
        Vec4::new(0.5, 1.0, 0.5, 0.0),
        Vec4::new(0.5, 0.5, 1.0, 0.0),
        Vec4::new(9.0, 0.5, -2.0, 0.0),
    ];
    let nearest = [value(0.0), value(113.0), value(112.0), value(103.0)];
    // Between the centres of eight texels (x 1 and 2, y 0 and 1, z 0 and
    // 1); clamped in x and y, between z 0 and 1; half way between texels 0
    // and 1 along x, 0 and 10 along y, 0 and 100 along z; clamped to
    // (3, 0, 0).
    let linear = [value(0.0), value(113.0), value(56.5), value(53.0), value(0.5), value(5.0), value(50.0), value(3.0)];
    for (filter, want) in [(FilterMode::Nearest, &nearest[..]), (FilterMode::Linear, &linear[..])] {
        for on in On::ALL.into_iter().filter(|on| on.available()) {
            let mut ctx = on.context();
            ctx.set_ray_type_count(0);
            let options = SamplerOptions {
                wrap: WrapMode::Clamp,
                filter,
                read: ReadMode::NormalizedFloat,
                index: IndexMode::ArrayIndex,
            };
            let volume = ctx
                .create_sampler_3d_from_texels(TexelData::R32F(texels.clone()), UVec3::new(4, 2, 2), options)
                .unwrap();
            let points = ctx.create_buffer(BufferType::Input, at[..want.len()].to_vec());
            let out = ctx.create_buffer(BufferType::Output, vec![Vec4::splat(-7.0); want.len()]);
            ctx.set_var(Scope::Context, "volume", volume).unwrap();
            ctx.set_var(Scope::Context, "at", points).unwrap();
            ctx.set_var(Scope::Context, "out", out).unwrap();
            let rg = ctx.create_program(&volume_at::PROGRAM);
            ctx.set_ray_generation_program(0, rg).unwrap();
            let report = ctx.launch_1d(0, want.len() as u32).unwrap();
            assert!(report.exceptions.is_empty(), "{on:?}: {:?}", report.exceptions);
            let got: Vec<Vec4> = ctx.read_buffer(out).unwrap();
            assert_eq!(got, want, "{filter:?} on {}", on.name());
        }
    }
}

/// Texel `i` of `data`, alone.
fn one(data: &TexelData, i: usize) -> TexelData {
    match data {
        TexelData::Rgba8(t) => TexelData::Rgba8(vec![t[i]]),
        TexelData::Rgba8Srgb(t) => TexelData::Rgba8Srgb(vec![t[i]]),
        TexelData::Rgba16F(t) => TexelData::Rgba16F(vec![t[i]]),
        TexelData::Rgba32F(t) => TexelData::Rgba32F(vec![t[i]]),
        TexelData::R8(t) => TexelData::R8(vec![t[i]]),
        TexelData::R32F(t) => TexelData::R32F(vec![t[i]]),
    }
}

#[test]
fn every_format_decodes_exactly_behind_3d_samplers_and_cube_maps_on_every_target() {
    for (name, data, read, want) in cases() {
        let n = want.len();
        for on in On::ALL.into_iter().filter(|on| on.available()) {
            let mut ctx = on.context();
            ctx.set_ray_type_count(0);
            // The texels as an n x 1 x 1 volume; cube face f of 1x1 is texel
            // f % n.
            let options =
                SamplerOptions { wrap: WrapMode::Clamp, filter: FilterMode::Nearest, read, ..Default::default() };
            let volume = ctx.create_sampler_3d_from_texels(data.clone(), UVec3::new(n as u32, 1, 1), options).unwrap();
            let faces = std::array::from_fn(|f| one(&data, f % n));
            let cube = ctx.create_sampler_cube_from_texels(faces, 1, FilterMode::Linear, read).unwrap();
            let out = ctx.create_buffer(BufferType::Output, vec![Vec4::splat(-7.0); 18]);
            ctx.set_var(Scope::Context, "volume", volume).unwrap();
            ctx.set_var(Scope::Context, "cube", cube).unwrap();
            ctx.set_var(Scope::Context, "out", out).unwrap();
            let rg = ctx.create_program(&read_volume_and_cube::PROGRAM);
            ctx.set_ray_generation_program(0, rg).unwrap();
            let report = ctx.launch_1d(0, 6).unwrap();
            assert!(report.exceptions.is_empty(), "{on:?}: {:?}", report.exceptions);
            let got: Vec<Vec4> = ctx.read_buffer(out).unwrap();
            for i in 0..6 {
                let at = format!("{name} on {}, index {i}", on.name());
                let texel = want[i.min(n - 1)];
                assert_eq!(got[3 * i].to_array().map(f32::to_bits), texel.to_array().map(f32::to_bits), "{at}: fetch");
                assert_eq!(got[3 * i + 1], texel, "{at}: volume sample");
                assert_eq!(got[3 * i + 2], want[i % n], "{at}: cube face");
            }
        }
    }
}

#[test]
fn bad_3d_and_cube_texels_are_refused_naming_the_sampler() {
    let mut ctx = Context::new();
    let options = SamplerOptions::default();
    let e = ctx.create_sampler_3d_from_texels(TexelData::R8(vec![1, 2, 3]), UVec3::new(2, 1, 2), options);
    assert_eq!(e.unwrap_err().to_string(), "sampler 0: 3 R8 texels for a 2x1x2 texture");
    let array = SamplerOptions { index: IndexMode::ArrayIndex, wrap: WrapMode::Repeat, ..options };
    let e = ctx.create_sampler_3d_from_texels(TexelData::R8(vec![1]), UVec3::ONE, array).unwrap_err().to_string();
    assert_eq!(
        e,
        "sampler 0: array-index coordinates (RT_TEXTURE_INDEX_ARRAY_INDEX) clamp to the edge, as GPUs' unnormalised coordinates do: use WrapMode::Clamp, not Repeat"
    );
    let faces = std::array::from_fn(|f| TexelData::Rgba16F(vec![[0; 4]; if f == 5 { 3 } else { 4 }]));
    let e = ctx.create_sampler_cube_from_texels(faces, 2, FilterMode::Linear, ReadMode::NormalizedFloat);
    assert_eq!(e.unwrap_err().to_string(), "sampler 0: cube face -z has 3 Rgba16F texels for a 2x2 face");
}
