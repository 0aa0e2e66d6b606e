//! `#[rt_enum]`s: a material kind (implicit discriminants) and a light
//! kind (`#[repr(u32)]`, explicit ones) as variables, payload and struct
//! fields and buffer elements, compared with `==`/`!=`, cast with `as`,
//! and matched exhaustively without `_` (as a statement and as an
//! expression, in a helper taking and returning the enum).
use rt_std::prelude::*;

/// How a surface scatters.
#[rt_enum]
pub enum Material {
    Diffuse,
    Metal,
    Glass,
}

/// A light's shape, with the discriminants a host format fixed.
#[rt_enum]
#[repr(u32)]
pub enum LightKind {
    Point = 1,
    Spot = 4,
    Area,
}

/// A light record in a buffer.
#[rt_struct]
pub struct Light {
    pub kind: LightKind,
    pub power: f32,
}

#[rt_payload]
pub struct KindShade {
    pub color: Vec3,
    pub hit: Material,
}

/// The material after a bounce: an exhaustive `match` as an expression.
#[rt_function]
pub fn next_material(m: Material) -> Material {
    match m {
        Material::Diffuse => Material::Metal,
        Material::Metal => Material::Glass,
        Material::Glass => Material::Diffuse,
    }
}

#[rt_program(ray_generation)]
pub fn enums(
    #[var] material: Material,
    #[var] lights: Buffer<Light>,
    #[var] mut kinds: RwBuffer<LightKind>,
    #[var] mut out: RwBuffer<Vec3>,
) {
    let i = launch_index().x;
    let light = lights[i];
    let mut prd = KindShade { color: Vec3::ZERO, hit: material };
    let mut weight = match light.kind {
        LightKind::Point => 1.0,
        LightKind::Spot => 0.5,
        LightKind::Area => light.power,
    };
    match next_material(prd.hit) {
        Material::Diffuse => prd.color = Vec3::splat(weight),
        Material::Metal | Material::Glass => {
            weight *= 2.0;
            prd.color = Vec3::new(weight, 0.0, 1.0);
        }
    }
    if prd.hit == Material::Glass || light.kind != LightKind::Spot {
        prd.hit = Material::Diffuse;
    }
    kinds[i] = light.kind;
    out[i] = prd.color + Vec3::splat((prd.hit as u32 + LightKind::Area as u32) as f32);
}

/// Attributes carrying the material an intersection program found.
#[rt_attributes]
pub struct SurfaceHit {
    pub normal: Vec3,
    pub material: Material,
}

#[rt_program(closest_hit)]
pub fn enum_attributes(prd: &mut KindShade, attr: &SurfaceHit) {
    prd.hit = attr.material;
    prd.color = match attr.material {
        Material::Diffuse => attr.normal,
        _ => Vec3::ONE,
    };
}

/// `let _ = attr;` silences an unused reference parameter.
#[rt_program(any_hit)]
pub fn enum_silenced(prd: &mut KindShade, attr: &SurfaceHit) {
    let _ = attr;
    prd.hit = Material::Glass;
}
