//! Texel formats of samplers (OptiX's buffer formats behind an
//! `RTtexturesampler`, with its read modes): the host decodes them to the
//! RGBA `f32` texels every sampler stores, on upload, as a GPU's sampler
//! would decode them on a read, so filtering sees the decoded values as it
//! does on a GPU. The texture takes 16 bytes a texel whatever its format.

use glam::Vec4;
use rt_std::{FilterMode, IndexMode, WrapMode};

/// Texels in one of the supported formats, row-major.
#[derive(Clone, Debug, PartialEq)]
pub enum TexelData {
    /// 8-bit RGBA, linear (`RT_FORMAT_UNSIGNED_BYTE4`, WebGPU `rgba8unorm`).
    Rgba8(Vec<[u8; 4]>),
    /// 8-bit RGBA with sRGB-encoded colour and linear alpha (WebGPU
    /// `rgba8unorm-srgb`).
    Rgba8Srgb(Vec<[u8; 4]>),
    /// Half-float RGBA, each channel the bits of an IEEE 754 binary16
    /// (`RT_FORMAT_HALF4`, WebGPU `rgba16float`).
    Rgba16F(Vec<[u16; 4]>),
    /// `f32` RGBA (`RT_FORMAT_FLOAT4`, WebGPU `rgba32float`).
    Rgba32F(Vec<Vec4>),
    /// One 8-bit channel (`RT_FORMAT_UNSIGNED_BYTE`, WebGPU `r8unorm`).
    R8(Vec<u8>),
    /// One `f32` channel (`RT_FORMAT_FLOAT`, WebGPU `r32float`).
    R32F(Vec<f32>),
}

/// How integer texels read (OptiX's `rtTextureSamplerSetReadMode`); float
/// formats read as they are in either mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum ReadMode {
    /// 8-bit channels read as `c / 255` in `[0, 1]`, sRGB ones decoded to
    /// linear (`RT_TEXTURE_READ_NORMALIZED_FLOAT`).
    #[default]
    NormalizedFloat,
    /// 8-bit channels read as their integer value, `0.0` to `255.0`, sRGB
    /// ones not decoded (`RT_TEXTURE_READ_ELEMENT_TYPE`; a program's texel
    /// is a `Vec4`, so the integers come as floats).
    ElementType,
}

/// The modes of a sampler made from [`TexelData`]
/// ([`Context::create_sampler_from_texels`](crate::Context::create_sampler_from_texels)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct SamplerOptions {
    /// Where coordinates outside the texture read (`Clamp` with
    /// [`IndexMode::ArrayIndex`]).
    pub wrap: WrapMode,
    /// How texels are filtered.
    pub filter: FilterMode,
    /// How integer texels read.
    pub read: ReadMode,
    /// Whether coordinates are normalised or in texels.
    pub index: IndexMode,
}

impl TexelData {
    /// The number of texels.
    pub fn len(&self) -> usize {
        match self {
            TexelData::Rgba8(t) | TexelData::Rgba8Srgb(t) => t.len(),
            TexelData::Rgba16F(t) => t.len(),
            TexelData::Rgba32F(t) => t.len(),
            TexelData::R8(t) => t.len(),
            TexelData::R32F(t) => t.len(),
        }
    }

    /// Whether there are no texels.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The format's name, as errors spell it.
    pub fn format_name(&self) -> &'static str {
        match self {
            TexelData::Rgba8(_) => "Rgba8",
            TexelData::Rgba8Srgb(_) => "Rgba8Srgb",
            TexelData::Rgba16F(_) => "Rgba16F",
            TexelData::Rgba32F(_) => "Rgba32F",
            TexelData::R8(_) => "R8",
            TexelData::R32F(_) => "R32F",
        }
    }

    /// The texels as a sampler reads them in mode `read`. One-channel
    /// formats read `(r, 0, 0, 1)`, as GPUs expand them; sRGB channels are
    /// decoded by the sRGB formula ([`srgb_to_linear`]), alpha kept linear.
    pub fn decode(&self, read: ReadMode) -> Vec<Vec4> {
        let normalized = read == ReadMode::NormalizedFloat;
        let unorm = |c: u8| if normalized { f32::from(c) / 255.0 } else { f32::from(c) };
        match self {
            TexelData::Rgba8(t) => t.iter().map(|c| Vec4::from_array(c.map(unorm))).collect(),
            TexelData::Rgba8Srgb(t) => t
                .iter()
                .map(|&[r, g, b, a]| {
                    if normalized {
                        Vec4::new(srgb_to_linear(r), srgb_to_linear(g), srgb_to_linear(b), unorm(a))
                    } else {
                        Vec4::from_array([r, g, b, a].map(unorm))
                    }
                })
                .collect(),
            TexelData::Rgba16F(t) => t.iter().map(|c| Vec4::from_array(c.map(f16_to_f32))).collect(),
            TexelData::Rgba32F(t) => t.clone(),
            TexelData::R8(t) => t.iter().map(|&r| Vec4::new(unorm(r), 0.0, 0.0, 1.0)).collect(),
            TexelData::R32F(t) => t.iter().map(|&r| Vec4::new(r, 0.0, 0.0, 1.0)).collect(),
        }
    }
}

/// An sRGB-encoded 8-bit channel as linear light, by the sRGB formula with
/// `c = code / 255`: `c / 12.92` for `c <= 0.04045`, else
/// `((c + 0.055) / 1.055)^2.4`, computed in `f64` and rounded to the nearest
/// `f32` (GPUs' sRGB formats are allowed a little error; this is the
/// formula's value). 0 is 0.0 and 255 is 1.0.
pub fn srgb_to_linear(code: u8) -> f32 {
    let c = f64::from(code) / 255.0;
    let linear = if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) };
    linear as f32
}

/// An IEEE 754 binary16 value (its bits) as the `f32` of the same value
/// (every half is exactly an `f32`): subnormals, infinities and NaN
/// (payload kept) included.
pub fn f16_to_f32(bits: u16) -> f32 {
    let sign = u32::from(bits >> 15) << 31;
    let exp = u32::from((bits >> 10) & 0x1f);
    let mant = u32::from(bits & 0x3ff);
    let magnitude = match exp {
        // Zero or subnormal: mant * 2^-24, exact in f32.
        0 => {
            let v = mant as f32 * (-24f32).exp2();
            return if sign == 0 { v } else { -v };
        }
        0x1f => 0x7f80_0000 | (mant << 13),
        _ => ((exp + 127 - 15) << 23) | (mant << 13),
    };
    f32::from_bits(sign | magnitude)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halves() {
        assert_eq!(f16_to_f32(0x3c00), 1.0);
        assert_eq!(f16_to_f32(0xc000), -2.0);
        assert_eq!(f16_to_f32(0x3555), 0.333_251_95);
        assert_eq!(f16_to_f32(0x7bff), 65504.0);
        assert_eq!(f16_to_f32(0x0001), 2f32.powi(-24));
        assert_eq!(f16_to_f32(0x8000).to_bits(), (-0.0f32).to_bits());
        assert_eq!(f16_to_f32(0x7c00), f32::INFINITY);
        assert!(f16_to_f32(0x7e00).is_nan());
    }

    #[test]
    fn srgb() {
        assert_eq!(srgb_to_linear(0), 0.0);
        assert_eq!(srgb_to_linear(255), 1.0);
        assert_eq!(srgb_to_linear(10), (10.0 / 255.0 / 12.92) as f32);
        assert_eq!(srgb_to_linear(128), 0.215_860_5);
    }
}
