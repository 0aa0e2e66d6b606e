//! Buffers and texture samplers: host storage that programs read through
//! rt-std's handles (`Buffer<T>`, `RwBuffer2d<T>`, `Sampler2d`, ...).
//!
//! A buffer stores `len + 1` elements of its Rust type: the extra one is the
//! sink rt-std's handles use for out-of-bounds indexing. Elements live in
//! `UnsafeCell`s because programs on many threads write output buffers
//! through handles while the context is shared.

use glam::Vec4;
use rt_std::program::TypeLayout;
use rt_std::{
    Buffer, Buffer2d, Buffer3d, RtData, RwBuffer, RwBuffer2d, RwBuffer3d, Sampler2d, Sampler3d, SamplerCube,
    SamplerModes,
};
use std::any::Any;
use std::cell::UnsafeCell;

/// How programs may use a buffer, as in OptiX.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BufferType {
    /// Written by the host, read by programs.
    Input,
    /// Written by programs, read back by the host.
    Output,
    /// Both.
    InputOutput,
}

impl BufferType {
    /// Whether programs may write the buffer (`Output`, `InputOutput`).
    pub fn writable_by_programs(self) -> bool {
        self != BufferType::Input
    }
}

/// Type-erased typed storage.
pub(crate) trait Storage: Send + Sync {
    fn layout(&self) -> TypeLayout;
    /// A handle of the element type for a program variable (`Buffer<T>`,
    /// `RwBuffer<T>`, `Buffer2d<T>`, `RwBuffer2d<T>`, `Buffer3d<T>` or
    /// `RwBuffer3d<T>`) over `size` (width, height, depth).
    fn handle(&self, dims: u32, writable: bool, size: [u32; 3]) -> Box<dyn Any + Send + Sync>;
    fn as_any(&self) -> &dyn Any;
    fn as_any_mut(&mut self) -> &mut dyn Any;
    /// Heap words of all elements (uploaded by the wgpu backend).
    fn to_words(&self, out: &mut Vec<u32>);
    /// Replaces the elements from heap words (read back from the GPU).
    fn read_words(&mut self, words: &[u32]);
}

pub(crate) struct Typed<T: RtData> {
    /// `len + 1` elements; the last is the out-of-bounds sink.
    cells: Box<[UnsafeCell<T>]>,
}

// SAFETY: elements are plain `Copy` data; concurrent writes to one element
// from two launch indices are a documented race, as on a GPU.
unsafe impl<T: RtData> Sync for Typed<T> {}
unsafe impl<T: RtData> Send for Typed<T> {}

impl<T: RtData> Typed<T> {
    pub fn new(data: Vec<T>) -> Self {
        let zero = T::read_words(&vec![0u32; T::LAYOUT.words as usize]);
        let cells = data.into_iter().chain(std::iter::once(zero)).map(UnsafeCell::new).collect();
        Typed { cells }
    }

    pub fn len(&self) -> usize {
        self.cells.len() - 1
    }

    fn ptr(&self) -> *mut T {
        // UnsafeCell<T> has T's layout.
        self.cells.as_ptr() as *mut T
    }

    pub fn to_vec(&self) -> Vec<T> {
        // SAFETY: no launch is running while the host holds `&self` here.
        self.cells[..self.len()].iter().map(|c| unsafe { *c.get() }).collect()
    }

    pub fn write(&mut self, data: &[T]) {
        for (c, v) in self.cells.iter_mut().zip(data) {
            *c.get_mut() = *v;
        }
    }
}

impl<T: RtData + Send + Sync> Storage for Typed<T> {
    fn layout(&self) -> TypeLayout {
        T::LAYOUT
    }

    fn handle(&self, dims: u32, writable: bool, [width, height, depth]: [u32; 3]) -> Box<dyn Any + Send + Sync> {
        let len = self.len() as u32;
        // SAFETY: the storage holds `len + 1` elements (the sink) and outlives
        // the launch that uses the handle (the context is borrowed for it).
        unsafe {
            match (dims, writable) {
                (3, true) => Box::new(RwBuffer3d::from_raw_parts(self.ptr(), width, height, depth)),
                (3, false) => Box::new(Buffer3d::from_raw_parts(self.ptr(), width, height, depth)),
                (2, true) => Box::new(RwBuffer2d::from_raw_parts(self.ptr(), width, height)),
                (2, false) => Box::new(Buffer2d::from_raw_parts(self.ptr(), width, height)),
                (_, true) => Box::new(RwBuffer::from_raw_parts(self.ptr(), len)),
                (_, false) => Box::new(Buffer::from_raw_parts(self.ptr(), len)),
            }
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }

    fn to_words(&self, out: &mut Vec<u32>) {
        let w = T::LAYOUT.words as usize;
        let start = out.len();
        out.resize(start + self.len() * w, 0);
        for (i, v) in self.to_vec().iter().enumerate() {
            v.write_words(&mut out[start + i * w..start + (i + 1) * w]);
        }
    }

    fn read_words(&mut self, words: &[u32]) {
        let w = T::LAYOUT.words as usize;
        let n = self.len();
        for (i, c) in self.cells[..n].iter_mut().enumerate() {
            if let Some(src) = words.get(i * w..(i + 1) * w) {
                *c.get_mut() = T::read_words(src);
            }
        }
    }
}

/// A buffer of the context.
pub(crate) struct BufferRec {
    pub storage: Box<dyn Storage>,
    pub ty: BufferType,
    pub width: u32,
    pub height: u32,
    /// 1 for 1D and 2D buffers.
    pub depth: u32,
    pub dims: u32,
    /// Whether launches leave what programs write on the device instead of
    /// reading it back ([`Context::set_buffer_device_local`](crate::Context::set_buffer_device_local)).
    pub device_local: bool,
    /// Bumped by every host write of the elements, so a backend holding
    /// newer words on its device knows when the host's replace them.
    pub host_version: u64,
}

impl BufferRec {
    pub fn new(storage: Box<dyn Storage>, ty: BufferType, [width, height, depth]: [u32; 3], dims: u32) -> BufferRec {
        BufferRec { storage, ty, width, height, depth, dims, device_local: false, host_version: 0 }
    }

    /// Its elements: width * height * depth (checked to fit a `u32` when
    /// it was created).
    pub fn len(&self) -> u32 {
        self.width * self.height * self.depth
    }

    pub fn type_name(&self) -> String {
        let base = match (self.dims, self.ty.writable_by_programs()) {
            (3, true) => "RwBuffer3d",
            (3, false) => "Buffer3d",
            (2, true) => "RwBuffer2d",
            (2, false) => "Buffer2d",
            (_, true) => "RwBuffer",
            (_, false) => "Buffer",
        };
        format!("{base}<{}> ({:?})", self.storage.layout().rust, self.ty)
    }
}

/// A texture sampler of the context: RGBA f32 texels with wrap and filter,
/// its mip levels one after the other from level 0.
pub(crate) struct SamplerRec {
    pub texels: Box<[Vec4]>,
    pub width: u32,
    pub height: u32,
    pub levels: u32,
    pub modes: SamplerModes,
    /// What programs read it as.
    pub shape: SamplerShape,
}

/// A sampler's shape: the program type that reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SamplerShape {
    /// `Sampler2d`: the mip levels one after the other.
    Flat,
    /// `Sampler3d` of this depth: one level, slice after slice.
    Volume(u32),
    /// `SamplerCube`: six `width x width` faces (+x, -x, +y, -y, +z, -z).
    Cube,
}

impl SamplerRec {
    pub fn handle(&self) -> Sampler2d {
        // SAFETY: `texels` holds the `levels` levels of a width x height
        // texture (checked by the context) and outlives the launch.
        unsafe { Sampler2d::from_raw_mip_parts(self.texels.as_ptr(), self.width, self.height, self.levels, self.modes) }
    }

    pub fn handle_3d(&self) -> Sampler3d {
        let depth = match self.shape {
            SamplerShape::Volume(d) => d,
            _ => 1,
        };
        let size = glam::UVec3::new(self.width, self.height, depth);
        // SAFETY: `texels` holds the `levels` levels of a width x height x
        // depth texture (checked by the context) and outlives the launch.
        unsafe { Sampler3d::from_raw_mip_parts(self.texels.as_ptr(), size, self.levels, self.modes) }
    }

    pub fn handle_cube(&self) -> SamplerCube {
        // SAFETY: `texels` holds the `levels` levels of six width x width
        // faces (checked by the context) and outlives the launch.
        unsafe {
            SamplerCube::from_raw_mip_parts(
                self.texels.as_ptr(),
                self.width,
                self.levels,
                self.modes.filter,
                self.modes.mip,
            )
        }
    }

    /// The program type a variable of this sampler must have.
    pub fn type_name(&self) -> &'static str {
        match self.shape {
            SamplerShape::Flat => "Sampler2d",
            SamplerShape::Volume(_) => "Sampler3d",
            SamplerShape::Cube => "SamplerCube",
        }
    }
}

/// A full mip chain of a 3D texture of `size` (texel `(x, y, z)` at
/// `x + y * width + z * width * height`): level 0 is `texels`, every next
/// level ([`rt_std::mip_level_size_3d`]) a box filter of the one before,
/// texel `(x, y, z)` the mean of the eight texels `(2x + i, 2y + j, 2z + k)`
/// for `i, j, k` in `{0, 1}`, each coordinate clamped to the level (as
/// [`generate_mip_levels`] does in two dimensions), down to 1x1x1. Empty
/// for texels of another count than the size's or an empty texture.
pub fn generate_mip_levels_3d(texels: &[Vec4], size: glam::UVec3) -> Vec<Vec<Vec4>> {
    let count = size.x as usize * size.y as usize * size.z as usize;
    if texels.is_empty() || texels.len() != count {
        return Vec::new();
    }
    let mut levels = vec![texels.to_vec()];
    let (mut w, mut h, mut d) = (size.x as usize, size.y as usize, size.z as usize);
    while w > 1 || h > 1 || d > 1 {
        let (nw, nh, nd) = ((w / 2).max(1), (h / 2).max(1), (d / 2).max(1));
        let above = levels.last().expect("level 0 is there");
        let at = |x: usize, y: usize, z: usize| above[x.min(w - 1) + (y.min(h - 1) + z.min(d - 1) * h) * w];
        let next = (0..nw * nh * nd)
            .map(|i| {
                let (x, y, z) = (2 * (i % nw), 2 * (i / nw % nh), 2 * (i / (nw * nh)));
                let mut sum = Vec4::ZERO;
                for (dx, dy, dz) in
                    [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)]
                {
                    sum += at(x + dx, y + dy, z + dz);
                }
                sum * 0.125
            })
            .collect();
        levels.push(next);
        (w, h, d) = (nw, nh, nd);
    }
    levels
}

/// A full mip chain of the `width x height` texels (row-major): level 0 is
/// `texels`, every next level ([`rt_std::mip_level_size`]) a box filter of
/// the one before, texel `(x, y)` being the mean of texels `(2x, 2y)`,
/// `(2x + 1, 2y)`, `(2x, 2y + 1)` and `(2x + 1, 2y + 1)`, `(a + b + c + d) /
/// 4`, each coordinate clamped to the level (so an axis of one texel
/// averages it with itself, and of an odd size the last row or column is
/// left out), down to 1x1. Empty for texels of another count than
/// `width * height` or an empty texture.
pub fn generate_mip_levels(texels: &[Vec4], width: u32, height: u32) -> Vec<Vec<Vec4>> {
    if texels.is_empty() || texels.len() != width as usize * height as usize {
        return Vec::new();
    }
    let mut levels = vec![texels.to_vec()];
    let (mut w, mut h) = (width as usize, height as usize);
    while w > 1 || h > 1 {
        let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
        let above = levels.last().expect("level 0 is there");
        let at = |x: usize, y: usize| above[x.min(w - 1) + y.min(h - 1) * w];
        let next = (0..nw * nh)
            .map(|i| {
                let (x, y) = (2 * (i % nw), 2 * (i / nw));
                (at(x, y) + at(x + 1, y) + at(x, y + 1) + at(x + 1, y + 1)) * 0.25
            })
            .collect();
        levels.push(next);
        (w, h) = (nw, nh);
    }
    levels
}
