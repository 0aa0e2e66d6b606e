//! Textures: a sampler's wrap and filter modes against rt-std's CPU
//! sampler.

use super::*;

pub(crate) fn textures_sample_with_wrap_and_filter(backend: On) {
    let (mut ctx, out) = camera(1.0, backend);
    let mut mesh = quad(0.0, 1.0);
    // Texture coordinates from -1 to 2: wrapping shows.
    mesh.texcoords = Some(vec![Vec2::new(-1.0, -1.0), Vec2::new(2.0, -1.0), Vec2::new(2.0, 2.0), Vec2::new(-1.0, 2.0)]);
    mesh_scene(&mut ctx, mesh, &textured::PROGRAM);
    let texels =
        vec![Vec4::new(1.0, 0.0, 0.0, 1.0), Vec4::new(0.0, 1.0, 0.0, 1.0), Vec4::new(0.0, 0.0, 1.0, 1.0), Vec4::ONE];
    for (wrap, filter) in [
        (WrapMode::Repeat, FilterMode::Nearest),
        (WrapMode::Clamp, FilterMode::Linear),
        (WrapMode::Mirror, FilterMode::Linear),
    ] {
        let tex = ctx.create_sampler(texels.clone(), 2, 2, wrap, filter).unwrap();
        ctx.set_var(Scope::Context, "tex", tex).unwrap();
        ctx.launch(0, W, W).unwrap();
        let img = ctx.read_buffer::<Vec4>(out).unwrap();
        // Compare every pixel with rt-std's CPU sampler at the same uv.
        let reference = unsafe { Sampler2d::from_raw_parts(texels.as_ptr(), 2, 2, wrap, filter) };
        for y in 0..W {
            for x in 0..W {
                let (wx, wy) = world(x, y, 1.0);
                let uv = Vec2::new(-1.0 + 3.0 * (wx + 1.0) / 2.0, -1.0 + 3.0 * (wy + 1.0) / 2.0);
                let expected = reference.sample(uv).truncate();
                let got = pixel(&img, x, y).truncate();
                assert!(
                    (got - expected).abs().max_element() < 2e-3,
                    "{wrap:?} {filter:?} at {x},{y}: {got} vs {expected}"
                );
            }
        }
    }
}
