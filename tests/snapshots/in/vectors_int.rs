//! Integer vectors: `IVec`/`UVec` constructors and constants, arithmetic,
//! bit operators and shifts by scalars and by vectors (also as compound
//! assignments), `abs`/`signum`/`min`/`max`/`clamp`/`dot`, reductions,
//! conversions with `as_vec*`/`as_ivec*`/`as_uvec*`, and pixel-grid math on
//! `launch_index()`.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn vectors_int(#[var] tile: UVec2, #[var] offset: IVec2, #[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let dim = launch_dim();
    let tile_id = idx / tile;
    let in_tile = idx % tile;
    let checker = (tile_id.x + tile_id.y) & 1;
    let centered = idx.as_ivec2() - (dim / 2).as_ivec2() + offset;
    let dist = centered.abs().max(IVec2::ONE).min(ivec2(1000, 1000)).clamp(IVec2::ZERO, IVec2::splat(512));
    let sgn = centered.signum() * IVec2::NEG_ONE + IVec2::X - IVec2::Y;
    let mixed = (idx << 1u32) ^ (dim >> UVec2::splat(2)) | uvec2(1, 2) & !UVec2::ZERO;
    let manhattan = dist.element_sum() + dist.dot(ivec2(1, -1)) + sgn.min_element() + sgn.max_element();
    let bits =
        mixed.element_product() + mixed.max_element() + UVec3::new(1, 2, 3).element_sum() + UVec2::X.x + UVec2::Y.y;
    let volume = ivec3(1, 2, 3) * 2 + 1 - IVec3::Z;
    let uv = (idx.as_vec2() + 0.5) / dim.as_vec2();
    let mut back = uv.as_uvec2() + (-uv).as_ivec2().as_uvec2() + volume.as_vec3().as_uvec3().xy();
    back <<= 2;
    back = back >> ivec2(1, 0);
    back &= 0xffff;
    back |= UVec2::X;
    back ^= in_tile;
    let mut signed = volume >> 1u32;
    signed = signed << uvec3(0, 1, 2);
    signed ^= -1;
    let corner = uvec4(in_tile.x, in_tile.y, checker, signed.y as u32) + UVec4::W;
    let color = vec4(uv.x, uv.y, checker as f32, 1.0) * (manhattan as f32 / 512.0) + corner.as_vec4() * 0.01;
    out[idx] = color + Vec4::splat((bits + back.x) as f32 * 1e-6);
}
