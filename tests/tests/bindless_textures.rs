//! Bindless textures (`BindlessSampler<S>`; OptiX texture ids,
//! `rtTextureSamplerGetId`, `rtTex2D<float4>(id, ..)`, `rtTex2DLod`,
//! `rtTex2DGrad`): a closest hit samples the texture of each instance's
//! material and primitive, chosen from a buffer of ids, exact with nearest
//! filtering, and hands the id back in its payload; ids in a `#[var]`, a
//! struct field and a callable's argument sample with `sample_lod`,
//! `sample_grad`, `fetch`, `size` and `levels` as the sampler itself does;
//! 3D and cube-map ids; a null id, an id of no sampler and an id of a
//! sampler of another shape raise `EXCEPTION_TEXTURE_ID_INVALID` and read
//! zero (still zero, silently, with the kind turned off), on every target;
//! the host's and the launch's checks name the sampler, the variable and
//! both shapes.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

#[rt_payload]
pub struct Shade {
    pub uv: Vec2,
    pub colour: Vec4,
    pub tex: BindlessSampler<Sampler2d>,
}

/// Two rays per quad (its triangle 0, then 1) at texel centres `uv`, then
/// one that misses; each ray also samples the id its payload brought back
/// at `(0.25, 0.25)`, the texture's texel (0, 0).
#[rt_program(ray_generation)]
pub fn shoot(#[var] top: Object, #[var] mut colours: RwBuffer<Vec4>, #[var] mut ids: RwBuffer<u32>) {
    let i = launch_index().x;
    let cx = (i / 2) as f32 * 3.0 - 3.0;
    let mut d = vec2(0.5, -0.5);
    if i % 2 == 1 {
        d = vec2(-0.5, 0.5);
    }
    // Texel centres of a 2x2 texture, a different one per ray.
    let uv = vec2(0.25 + 0.5 * (i % 2) as f32, 0.25 + 0.5 * ((i / 2) % 2) as f32);
    let mut prd = Shade { uv, colour: Vec4::splat(-1.0), tex: BindlessSampler::NONE };
    rt_trace(top, Ray::new(vec3(cx + d.x, d.y, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, 100.0), &mut prd);
    colours[i * 2] = prd.colour;
    colours[i * 2 + 1] = prd.tex.sample(vec2(0.25, 0.25));
    ids[i] = prd.tex.id();
}

/// The colour of the hit: the texture of the instance's material for the
/// hit primitive, `textures[material * 2 + primitive]`, sampled at the
/// payload's `uv`.
#[rt_program(closest_hit)]
pub fn textured(prd: &mut Shade, #[var] material: u32, #[var] textures: Buffer<BindlessSampler<Sampler2d>>) {
    let tex = textures[material * 2 + primitive_index()];
    prd.colour = tex.sample(prd.uv);
    prd.tex = tex;
}

#[rt_program(miss)]
pub fn sky(prd: &mut Shade) {
    prd.colour = vec4(0.0, 0.0, 9.0, 1.0);
}

fn quad_at(cx: f32) -> TriangleMesh {
    let mut quad = rt_tests::meshes::unit_quad();
    for p in &mut quad.positions {
        p.x += cx;
    }
    quad
}

/// Texel `j` (0..4) of texture `k`: distinct small integers.
fn texel(k: u32, j: u32) -> Vec4 {
    Vec4::new((10 * k + j) as f32, k as f32, j as f32, 1.0)
}

fn run_scene(on: On) -> (Vec<Vec4>, Vec<u32>, Vec<(u32, u32)>) {
    let mut ctx = on.context();
    ctx.set_ray_type_count(1);
    // Six 2x2 nearest textures; a 4x4 one first, so that ids are not
    // texture numbers.
    let _unused = ctx.create_sampler(vec![Vec4::ONE; 16], 4, 4, WrapMode::Clamp, FilterMode::Linear).unwrap();
    let ids: Vec<BindlessSampler<Sampler2d>> = (0..6)
        .map(|k| {
            let s = ctx
                .create_sampler((0..4).map(|j| texel(k, j)).collect(), 2, 2, WrapMode::Clamp, FilterMode::Nearest)
                .unwrap();
            ctx.sampler_id::<Sampler2d>(s).unwrap()
        })
        .collect();
    let textures = ctx.create_buffer(BufferType::Input, ids);
    ctx.set_var(Scope::Context, "textures", textures).unwrap();
    let ch = ctx.create_program(&textured::PROGRAM);
    // The quads at x = -3, 0, 3 have materials 2, 0 and 1.
    let mut instances = Vec::new();
    for (cx, material) in [(-3.0, 2u32), (0.0, 0), (3.0, 1)] {
        let m = ctx.create_material();
        ctx.set_closest_hit_program(m, 0, ch).unwrap();
        ctx.set_var(m, "material", material).unwrap();
        let g = ctx.create_triangles(quad_at(cx)).unwrap();
        instances.push(ctx.create_geometry_instance(g, &[m]).unwrap());
    }
    let top = ctx.create_geometry_group(&instances, Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let colours = ctx.create_buffer::<Vec4>(BufferType::Output, vec![Vec4::splat(7.0); 14]);
    let ids = ctx.create_buffer::<u32>(BufferType::Output, vec![77; 7]);
    ctx.set_var(Scope::Context, "colours", colours).unwrap();
    ctx.set_var(Scope::Context, "ids", ids).unwrap();
    let rg = ctx.create_program(&shoot::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&sky::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let report = ctx.launch_1d(0, 7).unwrap();
    let mut exceptions: Vec<(u32, u32)> = report.exceptions.iter().map(|e| (e.launch_index.x, e.code)).collect();
    exceptions.sort();
    (ctx.read_buffer(colours).unwrap(), ctx.read_buffer(ids).unwrap(), exceptions)
}

#[test]
fn a_closest_hit_samples_each_materials_texture_through_a_buffer_of_ids_on_every_target() {
    let mut want_colours = Vec::new();
    let mut want_ids = Vec::new();
    for i in 0..6u32 {
        let material = [2, 0, 1][(i / 2) as usize];
        // unit_quad's triangle 0 is hit by the first ray of each pair.
        let k = material * 2 + i % 2;
        // uv's texel: column i % 2, row (i / 2) % 2.
        let j = i % 2 + 2 * ((i / 2) % 2);
        want_colours.extend([texel(k, j), texel(k, 0)]);
        // Sampler 0 is the unused one: texture k's id is k + 2.
        want_ids.push(k + 2);
    }
    // The miss: its colour, and a null id, which reads zero and raises.
    want_colours.extend([Vec4::new(0.0, 0.0, 9.0, 1.0), Vec4::ZERO]);
    want_ids.push(0);
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let (colours, ids, exceptions) = run_scene(on);
        assert_eq!(colours, want_colours, "{}", on.name());
        assert_eq!(ids, want_ids, "{}", on.name());
        assert_eq!(exceptions, vec![(6, EXCEPTION_TEXTURE_ID_INVALID)], "{}", on.name());
    }
}

#[rt_struct]
pub struct Material {
    pub albedo: BindlessSampler<Sampler2d>,
    pub scale: f32,
}

/// A callable sampling the id it is given at a LOD.
#[rt_program(callable)]
pub fn at_lod(tex: BindlessSampler<Sampler2d>, lod: f32) -> Vec4 {
    tex.sample_lod(vec2(0.3, 0.7), lod)
}

/// Launch index `i` reads through `ids[i]` (a 2D id each) with every method
/// of a 2D sampler, and through the 3D and cube ids.
#[allow(clippy::too_many_arguments)]
#[rt_program(ray_generation)]
pub fn read_through_ids(
    #[var] mipped: BindlessSampler<Sampler2d>,
    #[var] ids: Buffer<BindlessSampler<Sampler2d>>,
    #[var] material: Material,
    #[var] lod: Callable<fn(BindlessSampler<Sampler2d>, f32) -> Vec4>,
    #[var] volume: BindlessSampler<Sampler3d>,
    #[var] cube: BindlessSampler<SamplerCube>,
    #[var] mut out: RwBuffer<Vec4>,
) {
    let i = launch_index().x;
    let tex = ids[i];
    let o = i * 8;
    let size = tex.size();
    out[o] = vec4(size.x as f32, size.y as f32, tex.levels() as f32, tex.id() as f32);
    out[o + 1] = tex.sample_lod(vec2(0.3, 0.7), 1.0);
    // One level-0 texel along u (1/8 of an 8x4 texture) and 4 along v: LOD 2.
    out[o + 2] = tex.sample_grad(vec2(0.3, 0.7), vec2(0.125, 0.0), vec2(0.0, 1.0));
    out[o + 3] = tex.fetch(uvec2(1, 0)) + tex.sample(vec2(0.9, 0.1));
    out[o + 4] = lod.call(tex, 2.5);
    let same = BindlessSampler::<Sampler2d>::from_id(tex.id());
    let mut flags = 0.0;
    if same == tex {
        flags += 1.0;
    }
    if tex == mipped {
        flags += 10.0;
    }
    if tex == BindlessSampler::NONE {
        flags += 100.0;
    }
    out[o + 5] = material.albedo.sample_lod(vec2(0.5, 0.5), i as f32) * material.scale + vec4(0.0, 0.0, 0.0, flags);
    out[o + 6] = volume.sample(vec3(0.75, 0.25, 0.75)) + volume.fetch(uvec3(0, 1, 0)) * 100.0;
    let s = volume.size();
    out[o + 7] = cube.sample_dir(vec3(0.0, -1.0, 0.0)) + vec4(cube.size() as f32, s.x as f32, s.y as f32, s.z as f32);
}

/// Level `l`'s colour (small integers, so every blend is exact).
fn colour(l: u32) -> Vec4 {
    let l = l as f32;
    Vec4::new(1.0 + 8.0 * l, 2.0 * l, 16.0 - 4.0 * l, 1.0)
}

/// What `read_through_ids` reads, and the exceptions it raised.
fn run_reads(on: On, id_exceptions: bool) -> (Vec<Vec4>, Vec<(u32, u32)>) {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    ctx.set_exception_enabled(ExceptionKind::TextureIdInvalid, id_exceptions);
    // Sampler 0: 8x4 with 4 levels of one colour each, nearest.
    let levels = (0..4).map(|l| vec![colour(l); (8usize >> l) * (4usize >> l).max(1)]).collect();
    let mipped =
        ctx.create_sampler_mipmapped(levels, 8, 4, WrapMode::Repeat, FilterMode::Nearest, MipFilter::Linear).unwrap();
    // Sampler 1: 2x2, one level.
    let flat =
        ctx.create_sampler((0..4).map(|j| texel(3, j)).collect(), 2, 2, WrapMode::Clamp, FilterMode::Nearest).unwrap();
    // Sampler 2: a 2x2x2 volume, texel (x, y, z) = x + 2y + 4z.
    let vol_texels = (0..8).map(|i| Vec4::splat(i as f32)).collect();
    let volume = ctx.create_sampler_3d(vol_texels, UVec3::splat(2), WrapMode::Clamp, FilterMode::Nearest).unwrap();
    // Sampler 3: a cube map of 1x1 faces, face k = 10k.
    let faces = std::array::from_fn(|k| vec![Vec4::splat(10.0 * k as f32)]);
    let cube = ctx.create_sampler_cube(faces, 1, FilterMode::Nearest).unwrap();
    let mipped_id = ctx.sampler_id::<Sampler2d>(mipped).unwrap();
    let flat_id = ctx.sampler_id::<Sampler2d>(flat).unwrap();
    let volume_id = ctx.sampler_id::<Sampler3d>(volume).unwrap();
    let cube_id = ctx.sampler_id::<SamplerCube>(cube).unwrap();
    // Entries: the mipped texture, the flat one, none, the cube map read
    // as a 2D texture (another shape), an id of no sampler.
    let entries = vec![
        mipped_id,
        flat_id,
        BindlessSampler::NONE,
        BindlessSampler::from_id(cube_id.id()),
        BindlessSampler::from_id(99),
    ];
    let ids = ctx.create_buffer(BufferType::Input, entries);
    let out = ctx.create_buffer(BufferType::Output, vec![Vec4::splat(-1.0); 8 * 5]);
    let callable = ctx.create_program(&at_lod::PROGRAM);
    let lod = ctx.callable_id::<fn(BindlessSampler<Sampler2d>, f32) -> Vec4>(callable).unwrap();
    ctx.set_var(Scope::Context, "mipped", mipped_id).unwrap();
    ctx.set_var(Scope::Context, "ids", ids).unwrap();
    ctx.set_var(Scope::Context, "material", Material { albedo: mipped_id, scale: 2.0 }).unwrap();
    ctx.set_var(Scope::Context, "lod", lod).unwrap();
    ctx.set_var(Scope::Context, "volume", volume_id).unwrap();
    ctx.set_var(Scope::Context, "cube", cube_id).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&read_through_ids::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch_1d(0, 5).unwrap();
    let mut exceptions: Vec<(u32, u32)> = report.exceptions.iter().map(|e| (e.launch_index.x, e.code)).collect();
    exceptions.sort();
    (ctx.read_buffer(out).unwrap(), exceptions)
}

#[test]
fn ids_in_variables_buffers_structs_and_callables_sample_the_same_on_every_target() {
    let c = colour;
    let mix = |a: Vec4, b: Vec4, t: f32| a * (1.0 - t) + b * t;
    let mut want = Vec::new();
    for i in 0..5u32 {
        let (size, levels, id, flags) = match i {
            0 => (Vec2::new(8.0, 4.0), 4.0, 1.0, 11.0),
            1 => (Vec2::splat(2.0), 1.0, 2.0, 1.0),
            2 => (Vec2::ZERO, 1.0, 0.0, 101.0),
            3 => (Vec2::ZERO, 1.0, 4.0, 1.0),
            _ => (Vec2::ZERO, 1.0, 99.0, 1.0),
        };
        want.push(Vec4::new(size.x, size.y, levels, id));
        let reads = match i {
            // LOD 1; the footprint's LOD 2; texel (1, 0) plus the sample at
            // texel (7, 0), both level 0; LOD 2.5 blends levels 2 and 3.
            0 => [c(1), c(2), c(0) * 2.0, mix(c(2), c(3), 0.5)],
            // One level: every LOD reads it; uv (0.3, 0.7) is texel (0, 1),
            // (0.9, 0.1) texel (1, 0).
            1 => [texel(3, 2), texel(3, 2), texel(3, 1) * 2.0, texel(3, 2)],
            // No sampler of this shape: zero.
            _ => [Vec4::ZERO; 4],
        };
        want.extend(reads);
        // The material's texture (the mipped one) at LOD i, scaled by 2.
        want.push(c(i.min(3)) * 2.0 + Vec4::new(0.0, 0.0, 0.0, flags));
        // Volume: texel (1, 0, 1) = 5, plus texel (0, 1, 0) = 2 times 100.
        want.push(Vec4::splat(205.0));
        // Cube: face -y (3) = 30, its size 1, the volume's 2x2x2.
        want.push(Vec4::new(31.0, 32.0, 32.0, 32.0));
    }
    for id_exceptions in [true, false] {
        let raised: Vec<(u32, u32)> =
            if id_exceptions { [2, 3, 4].map(|i| (i, EXCEPTION_TEXTURE_ID_INVALID)).to_vec() } else { Vec::new() };
        for on in On::ALL.into_iter().filter(|on| on.available()) {
            let (got, exceptions) = run_reads(on, id_exceptions);
            for (i, (g, w)) in got.chunks(8).zip(want.chunks(8)).enumerate() {
                assert_eq!(g, w, "{} index {i} (exceptions on: {id_exceptions})", on.name());
            }
            assert_eq!(exceptions, raised, "{} (exceptions on: {id_exceptions})", on.name());
        }
    }
}

#[rt_program(ray_generation)]
pub fn sample_one(#[var] tex: BindlessSampler<Sampler2d>, #[var] mut out: RwBuffer<Vec4>) {
    out[0] = tex.sample(vec2(0.5, 0.5));
}

#[test]
fn ids_of_another_shape_or_of_no_sampler_are_refused_naming_the_sampler_and_variable() {
    let mut ctx = Context::new();
    ctx.set_ray_type_count(0);
    let faces = std::array::from_fn(|_| vec![Vec4::ONE]);
    let cube = ctx.create_sampler_cube(faces, 1, FilterMode::Nearest).unwrap();
    let e = ctx.sampler_id::<Sampler2d>(cube).unwrap_err().to_string();
    assert!(e.contains("sampler 0") && e.contains("`Sampler2d`") && e.contains("`SamplerCube`"), "{e}");
    let out = ctx.create_buffer::<Vec4>(BufferType::Output, vec![Vec4::ZERO]);
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&sample_one::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        on.apply(&mut ctx);
        // The cube map's id set as a 2D id: refused at launch.
        let cube_id = ctx.sampler_id::<SamplerCube>(cube).unwrap();
        ctx.set_var(Scope::Context, "tex", BindlessSampler::<Sampler2d>::from_id(cube_id.id())).unwrap();
        let e = ctx.launch_1d(0, 1).unwrap_err().to_string();
        assert!(
            e.contains("`tex`") && e.contains("BindlessSampler<Sampler2d>") && e.contains("sampler 0, a `SamplerCube`"),
            "{}: {e}",
            on.name()
        );
        ctx.set_var(Scope::Context, "tex", BindlessSampler::<Sampler2d>::from_id(7)).unwrap();
        let e = ctx.launch_1d(0, 1).unwrap_err().to_string();
        assert!(e.contains("`tex`") && e.contains("id 7, which names no sampler"), "{}: {e}", on.name());
        // A null id is a value: the launch runs, the read raises.
        ctx.set_var(Scope::Context, "tex", BindlessSampler::<Sampler2d>::NONE).unwrap();
        let report = ctx.launch_1d(0, 1).unwrap();
        let codes: Vec<u32> = report.exceptions.iter().map(|e| e.code).collect();
        assert_eq!(codes, vec![EXCEPTION_TEXTURE_ID_INVALID], "{}", on.name());
    }
}

/// Launch index `i` fetches texel (0, 0) of `ids[i]`.
#[rt_program(ray_generation)]
pub fn fetch_each(#[var] ids: Buffer<BindlessSampler<Sampler2d>>, #[var] mut out: RwBuffer<Vec4>) {
    let i = launch_index().x;
    out[i] = ids[i].fetch(uvec2(0, 0));
}

/// Samplers of `sizes` (square, each texel `(k, side, 0, 1)` for sampler
/// `k`), read through a buffer of their ids: the fetched texels.
#[allow(clippy::result_large_err)] // rt_runtime::Result, as the context returns it.
fn fetch_all(ctx: &mut Context, sizes: &[u32]) -> Result<Vec<Vec4>> {
    ctx.set_ray_type_count(0);
    let mut ids = Vec::new();
    for (k, &side) in sizes.iter().enumerate() {
        let texels = vec![Vec4::new(k as f32, side as f32, 0.0, 1.0); (side * side) as usize];
        let s = ctx.create_sampler(texels, side, side, WrapMode::Clamp, FilterMode::Nearest)?;
        ids.push(ctx.sampler_id::<Sampler2d>(s)?);
    }
    let ids = ctx.create_buffer(BufferType::Input, ids);
    let out = ctx.create_buffer(BufferType::Output, vec![Vec4::splat(-1.0); sizes.len()]);
    ctx.set_var(Scope::Context, "ids", ids)?;
    ctx.set_var(Scope::Context, "out", out)?;
    let rg = ctx.create_program(&fetch_each::PROGRAM);
    ctx.set_ray_generation_program(0, rg)?;
    let report = ctx.launch_1d(0, sizes.len() as u32)?;
    assert!(report.exceptions.is_empty(), "{:?}", report.exceptions);
    ctx.read_buffer(out)
}

#[test]
fn more_samplers_than_an_adapter_binds_are_sampled_through_ids_on_every_target() {
    // 40 samplers: more than WebGPU's default 16 sampled textures a stage;
    // ids take no binding.
    let sizes: Vec<u32> = (0..40).map(|k| 1 + k % 3).collect();
    let want: Vec<Vec4> = sizes.iter().enumerate().map(|(k, &s)| Vec4::new(k as f32, s as f32, 0.0, 1.0)).collect();
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        assert_eq!(fetch_all(&mut on.context(), &sizes).unwrap(), want, "{}", on.name());
    }
}

#[test]
fn a_heap_past_one_binding_names_the_sampler_that_crosses_it() {
    let device = || {
        let instance = rt_runtime::backend::wgpu::instance();
        let adapter = pollster::block_on(instance.request_adapter(&Default::default())).expect("an adapter (lavapipe)");
        let limits = ::wgpu::Limits {
            max_storage_buffer_binding_size: 1 << 20,
            max_storage_buffers_per_shader_stage: adapter.limits().max_storage_buffers_per_shader_stage.min(5),
            ..::wgpu::Limits::downlevel_defaults()
        };
        let descriptor = ::wgpu::DeviceDescriptor { required_limits: limits, ..Default::default() };
        let (device, queue) = pollster::block_on(adapter.request_device(&descriptor)).unwrap();
        (device, queue, adapter.get_info())
    };
    // Two 128 x 128 samplers (256 KiB each) fit a 1 MiB heap; a third of
    // 256 x 256 (1 MiB) ends past it.
    let (d, q, info) = device();
    let mut ctx = Context::new();
    ctx.use_wgpu_device(d, q, info);
    let got = fetch_all(&mut ctx, &[128, 128]).unwrap();
    assert_eq!(got, vec![Vec4::new(0.0, 128.0, 0.0, 1.0), Vec4::new(1.0, 128.0, 0.0, 1.0)]);
    let (d, q, info) = device();
    let mut ctx = Context::new();
    ctx.use_wgpu_device(d, q, info);
    let e = fetch_all(&mut ctx, &[128, 128, 256]).unwrap_err().to_string();
    assert!(e.starts_with("sampler 2: its 262144 words of texels end at word"), "{e}");
    assert!(e.contains("binds at most 1 MiB per storage buffer"), "{e}");
    // The context stays usable: on the CPU backend, which has no binding.
    ctx.set_backend(Backend::Cpu);
    let report = ctx.launch_1d(0, 3).unwrap();
    assert!(report.exceptions.is_empty());
}
