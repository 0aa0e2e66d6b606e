//! Buffer handles: [`Buffer`], [`RwBuffer`], [`Buffer2d`], [`RwBuffer2d`],
//! [`Buffer3d`], [`RwBuffer3d`].
//!
//! A handle is a `Copy` view of element storage that the runtime owns. On the
//! GPU the elements live in the runtime's buffer heap in the packed layout of
//! [`RtData`]; on the CPU they are ordinary Rust values of type `T`, so the
//! handle can hand out references.
//!
//! # Bounds
//! Every access is checked. An index outside the buffer raises
//! [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] in the current execution context
//! (the exception program runs after the program returns) and never touches
//! memory outside the storage: a load returns the value whose words are all
//! zero, a store is dropped, and `Index`/`IndexMut` return a reference to a
//! scratch *sink* element that the runtime allocates after the last element
//! and that is zeroed before each out-of-bounds reference is handed out.
//!
//! # Concurrency
//! Handles are `Send + Sync`: the CPU backend runs launch indices on several
//! threads, all sharing the storage. As on a GPU, two launch indices
//! accessing the same element where one of them writes is a race; in Rust it
//! is undefined behaviour, so programs must keep their writes disjoint (the
//! usual one output element per launch index), and so must out-of-bounds
//! accesses through `Index`/`IndexMut`, which share the sink. A reference from
//! `Index`/`IndexMut` must not be held while another copy of the handle
//! writes the same element (programs cannot: the subset has no reference
//! locals). Elements that several launch indices update go through the
//! atomic updates of [`crate::atomic`] (`atomic_add`, ...), which may race
//! with each other but not with plain accesses.

use core::fmt;
use core::marker::PhantomData;
use core::ops::{Index, IndexMut};

use glam::{UVec2, UVec3};

use crate::cpu;
use crate::data::{RtData, zeroed};
use crate::intrinsics::EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS;

/// The storage behind every handle: `count` elements followed by the sink.
struct Elements<T> {
    ptr: *mut T,
    count: usize,
    _marker: PhantomData<T>,
}

impl<T> Clone for Elements<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Elements<T> {}

impl<T: RtData> Elements<T> {
    /// # Safety
    /// `ptr` points to `count + 1` initialised elements as the handles'
    /// `from_raw_parts` describe.
    unsafe fn new(ptr: *mut T, count: usize) -> Self {
        Elements { ptr, count, _marker: PhantomData }
    }

    /// The element at `index`, or `None` after raising the exception.
    fn element(&self, index: Option<usize>) -> Option<*mut T> {
        match index {
            // SAFETY: in bounds of the storage given to `new`.
            Some(i) if i < self.count => Some(unsafe { self.ptr.add(i) }),
            _ => {
                cpu::raise(EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS);
                None
            }
        }
    }

    /// The element at `index`, or the freshly zeroed sink.
    fn element_or_sink(&self, index: Option<usize>) -> *mut T {
        self.element(index).unwrap_or_else(|| {
            // SAFETY: the sink is the element after the last one, writable
            // scratch by the `from_raw_parts` contract.
            unsafe {
                let sink = self.ptr.add(self.count);
                sink.write(zeroed());
                sink
            }
        })
    }

    fn load(&self, index: Option<usize>) -> T {
        match self.element(index) {
            // SAFETY: a live, initialised element (races excluded by contract).
            Some(p) => unsafe { p.read() },
            None => zeroed(),
        }
    }

    fn store(&self, index: Option<usize>, value: T) {
        if let Some(p) = self.element(index) {
            // SAFETY: as in `load`; the storage is writable for `Rw` handles.
            unsafe { p.write(value) }
        }
    }

    fn get(&self, index: Option<usize>) -> &T {
        // SAFETY: a live element or the sink; see the module's concurrency
        // rules for aliasing.
        unsafe { &*self.element_or_sink(index) }
    }

    #[allow(clippy::mut_from_ref)] // The storage is shared by design, as on a GPU.
    fn get_mut(&self, index: Option<usize>) -> &mut T {
        // SAFETY: as in `get`.
        unsafe { &mut *self.element_or_sink(index) }
    }
}

/// The linear index of `i` in a buffer of `len` elements, if in bounds.
fn index_1d(i: u32, len: u32) -> Option<usize> {
    (i < len).then_some(i as usize)
}

/// The row-major linear index `x + y * width` of `idx`, if in bounds.
fn index_2d(idx: UVec2, size: UVec2) -> Option<usize> {
    (idx.x < size.x && idx.y < size.y).then(|| idx.x as usize + idx.y as usize * size.x as usize)
}

/// Element `(x, y, z)` of a row-major 3D buffer: `x + (y + z * height) *
/// width`, if inside.
fn index_3d(idx: UVec3, size: UVec3) -> Option<usize> {
    (idx.x < size.x && idx.y < size.y && idx.z < size.z)
        .then(|| idx.x as usize + (idx.y as usize + idx.z as usize * size.y as usize) * size.x as usize)
}

macro_rules! handle_traits {
    ($name:ident) => {
        impl<T: RtData> Clone for $name<T> {
            fn clone(&self) -> Self {
                *self
            }
        }
        impl<T: RtData> Copy for $name<T> {}
        // SAFETY: the handle is a pointer to shared storage; data races
        // between threads are excluded by the `from_raw_parts` contract and
        // the rules in the module docs, as on a GPU.
        unsafe impl<T: RtData + Send + Sync> Send for $name<T> {}
        // SAFETY: as for `Send`.
        unsafe impl<T: RtData + Send + Sync> Sync for $name<T> {}
    };
}

/// A read-only 1D buffer of `T`, indexed by `u32`.
///
/// See the [module docs](self) for bounds checks and concurrency.
#[doc(alias = "rtBuffer")]
pub struct Buffer<T: RtData> {
    elements: Elements<T>,
    len: u32,
}

handle_traits!(Buffer);

impl<T: RtData> Buffer<T> {
    /// A handle to the `len` elements at `ptr`. Host side only: the runtime
    /// creates handles, programs receive them as variables.
    ///
    /// # Safety
    /// - `ptr` points to `len + 1` initialised, properly aligned `T`s: the
    ///   elements, then a sink element that out-of-bounds `Index` accesses
    ///   overwrite (so the storage must be writable, though the elements are
    ///   never written through this handle).
    /// - The storage stays valid, and is not moved or freed, while any copy of
    ///   the handle is used.
    /// - Nothing writes an element while a program may read it (the runtime
    ///   writes buffers only between launches).
    pub unsafe fn from_raw_parts(ptr: *const T, len: u32) -> Self {
        // SAFETY: forwarded to the caller.
        Buffer { elements: unsafe { Elements::new(ptr.cast_mut(), len as usize) }, len }
    }

    /// Number of elements.
    ///
    /// Program kinds: all.
    pub fn len(&self) -> u32 {
        self.len
    }

    /// Whether the buffer has no elements.
    ///
    /// Program kinds: all.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The element at `i`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns all-zero words.
    ///
    /// Program kinds: all.
    pub fn load(&self, i: u32) -> T {
        self.elements.load(index_1d(i, self.len))
    }

    /// `self[i]`, borrowed for as long as the storage lives rather than the
    /// handle (a bindless id's handle is a copy; the storage outlives the
    /// launch, by the `from_raw_parts` contract).
    pub(crate) fn element_ref<'s>(self, i: u32) -> &'s T {
        // SAFETY: a live element or the sink, as in `Elements::get`.
        unsafe { &*self.elements.element_or_sink(index_1d(i, self.len)) }
    }
}

impl<T: RtData> Index<u32> for Buffer<T> {
    type Output = T;

    /// `buffer[i]`: the element at `i`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns the zeroed sink.
    ///
    /// Program kinds: all.
    fn index(&self, i: u32) -> &T {
        self.elements.get(index_1d(i, self.len))
    }
}

impl<T: RtData> fmt::Debug for Buffer<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Buffer").field("element", &T::LAYOUT.rust).field("len", &self.len).finish()
    }
}

/// A read-write 1D buffer of `T`, indexed by `u32`.
///
/// See the [module docs](self) for bounds checks and concurrency.
#[doc(alias = "rtBuffer")]
pub struct RwBuffer<T: RtData> {
    elements: Elements<T>,
    len: u32,
}

handle_traits!(RwBuffer);

impl<T: RtData> RwBuffer<T> {
    /// A handle to the `len` elements at `ptr`. Host side only: the runtime
    /// creates handles, programs receive them as variables.
    ///
    /// # Safety
    /// - `ptr` points to `len + 1` initialised, properly aligned, writable
    ///   `T`s: the elements, then a sink element that out-of-bounds
    ///   `Index`/`IndexMut` accesses overwrite.
    /// - The storage stays valid, and is not moved, freed or accessed other
    ///   than through handles, while any copy of the handle is used.
    pub unsafe fn from_raw_parts(ptr: *mut T, len: u32) -> Self {
        // SAFETY: forwarded to the caller.
        RwBuffer { elements: unsafe { Elements::new(ptr, len as usize) }, len }
    }

    /// Number of elements.
    ///
    /// Program kinds: all.
    pub fn len(&self) -> u32 {
        self.len
    }

    /// Whether the buffer has no elements.
    ///
    /// Program kinds: all.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The element at `i`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns all-zero words.
    ///
    /// Program kinds: all.
    pub fn load(&self, i: u32) -> T {
        self.elements.load(index_1d(i, self.len))
    }

    /// Writes `v` at `i`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and writes nothing.
    ///
    /// Program kinds: all.
    pub fn store(&self, i: u32, v: T) {
        self.elements.store(index_1d(i, self.len), v)
    }

    /// The element at `i`, or `None` after raising the exception (for the
    /// atomic updates, see [`crate::atomic`]).
    pub(crate) fn element(&self, i: u32) -> Option<*mut T> {
        self.elements.element(index_1d(i, self.len))
    }

    /// `self[i]` for as long as the storage lives, as
    /// [`Buffer::element_ref`].
    pub(crate) fn element_ref<'s>(self, i: u32) -> &'s T {
        // SAFETY: a live element or the sink, as in `Elements::get`.
        unsafe { &*self.elements.element_or_sink(index_1d(i, self.len)) }
    }
}

impl<T: RtData> Index<u32> for RwBuffer<T> {
    type Output = T;

    /// `buffer[i]`: the element at `i`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns the zeroed sink.
    ///
    /// Program kinds: all.
    fn index(&self, i: u32) -> &T {
        self.elements.get(index_1d(i, self.len))
    }
}

impl<T: RtData> IndexMut<u32> for RwBuffer<T> {
    /// `buffer[i] = v`: the element at `i`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns the zeroed sink,
    /// so the write is lost.
    ///
    /// Program kinds: all.
    fn index_mut(&mut self, i: u32) -> &mut T {
        self.elements.get_mut(index_1d(i, self.len))
    }
}

impl<T: RtData> fmt::Debug for RwBuffer<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("RwBuffer").field("element", &T::LAYOUT.rust).field("len", &self.len).finish()
    }
}

/// A read-only 2D buffer of `T`, indexed by `UVec2` (`x` the column, `y` the
/// row; element `(x, y)` is stored at `x + y * width`).
///
/// See the [module docs](self) for bounds checks and concurrency.
#[doc(alias = "rtBuffer")]
pub struct Buffer2d<T: RtData> {
    elements: Elements<T>,
    size: UVec2,
}

handle_traits!(Buffer2d);

impl<T: RtData> Buffer2d<T> {
    /// A handle to the `width * height` elements at `ptr`, row-major. Host
    /// side only: the runtime creates handles, programs receive them as
    /// variables.
    ///
    /// # Safety
    /// As [`Buffer::from_raw_parts`] with `len = width * height`: `ptr`
    /// points to `width * height + 1` elements, the last being the sink.
    pub unsafe fn from_raw_parts(ptr: *const T, width: u32, height: u32) -> Self {
        let count = width as usize * height as usize;
        // SAFETY: forwarded to the caller.
        Buffer2d { elements: unsafe { Elements::new(ptr.cast_mut(), count) }, size: UVec2::new(width, height) }
    }

    /// Width and height in elements.
    ///
    /// Program kinds: all.
    pub fn size(&self) -> UVec2 {
        self.size
    }

    /// The element at `idx`; out of bounds (in either axis), raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns all-zero words.
    ///
    /// Program kinds: all.
    pub fn load(&self, idx: UVec2) -> T {
        self.elements.load(index_2d(idx, self.size))
    }
}

impl<T: RtData> Index<UVec2> for Buffer2d<T> {
    type Output = T;

    /// `buffer[idx]`: the element at `idx`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns the zeroed sink.
    ///
    /// Program kinds: all.
    fn index(&self, idx: UVec2) -> &T {
        self.elements.get(index_2d(idx, self.size))
    }
}

impl<T: RtData> fmt::Debug for Buffer2d<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Buffer2d").field("element", &T::LAYOUT.rust).field("size", &self.size).finish()
    }
}

/// A read-write 2D buffer of `T`, indexed by `UVec2` (`x` the column, `y`
/// the row; element `(x, y)` is stored at `x + y * width`): the usual output
/// image.
///
/// See the [module docs](self) for bounds checks and concurrency.
#[doc(alias = "rtBuffer")]
pub struct RwBuffer2d<T: RtData> {
    elements: Elements<T>,
    size: UVec2,
}

handle_traits!(RwBuffer2d);

impl<T: RtData> RwBuffer2d<T> {
    /// A handle to the `width * height` elements at `ptr`, row-major. Host
    /// side only: the runtime creates handles, programs receive them as
    /// variables.
    ///
    /// # Safety
    /// As [`RwBuffer::from_raw_parts`] with `len = width * height`: `ptr`
    /// points to `width * height + 1` elements, the last being the sink.
    pub unsafe fn from_raw_parts(ptr: *mut T, width: u32, height: u32) -> Self {
        let count = width as usize * height as usize;
        // SAFETY: forwarded to the caller.
        RwBuffer2d { elements: unsafe { Elements::new(ptr, count) }, size: UVec2::new(width, height) }
    }

    /// Width and height in elements.
    ///
    /// Program kinds: all.
    pub fn size(&self) -> UVec2 {
        self.size
    }

    /// The element at `idx`; out of bounds (in either axis), raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns all-zero words.
    ///
    /// Program kinds: all.
    pub fn load(&self, idx: UVec2) -> T {
        self.elements.load(index_2d(idx, self.size))
    }

    /// Writes `v` at `idx`; out of bounds (in either axis), raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and writes nothing.
    ///
    /// Program kinds: all.
    pub fn store(&self, idx: UVec2, v: T) {
        self.elements.store(index_2d(idx, self.size), v)
    }

    /// The element at `idx`, or `None` after raising the exception.
    pub(crate) fn element(&self, idx: UVec2) -> Option<*mut T> {
        self.elements.element(index_2d(idx, self.size))
    }
}

impl<T: RtData> Index<UVec2> for RwBuffer2d<T> {
    type Output = T;

    /// `buffer[idx]`: the element at `idx`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns the zeroed sink.
    ///
    /// Program kinds: all.
    fn index(&self, idx: UVec2) -> &T {
        self.elements.get(index_2d(idx, self.size))
    }
}

impl<T: RtData> IndexMut<UVec2> for RwBuffer2d<T> {
    /// `buffer[idx] = v`: the element at `idx`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns the zeroed sink,
    /// so the write is lost.
    ///
    /// Program kinds: all.
    fn index_mut(&mut self, idx: UVec2) -> &mut T {
        self.elements.get_mut(index_2d(idx, self.size))
    }
}

impl<T: RtData> fmt::Debug for RwBuffer2d<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("RwBuffer2d").field("element", &T::LAYOUT.rust).field("size", &self.size).finish()
    }
}

/// A read-only 3D buffer of `T` (OptiX's `rtBuffer<T, 3>`), indexed by
/// `UVec3`: element `(x, y, z)` is stored at `x + (y + z * height) * width`
/// (slices of rows).
///
/// See the [module docs](self) for bounds checks and concurrency.
#[doc(alias = "rtBuffer")]
pub struct Buffer3d<T: RtData> {
    elements: Elements<T>,
    size: UVec3,
}

handle_traits!(Buffer3d);

impl<T: RtData> Buffer3d<T> {
    /// A handle to the `width * height * depth` elements at `ptr`. Host
    /// side only: the runtime creates handles, programs receive them as
    /// variables.
    ///
    /// # Safety
    /// As [`Buffer::from_raw_parts`] with `len = width * height * depth`:
    /// `ptr` points to that many elements and the sink after them.
    pub unsafe fn from_raw_parts(ptr: *const T, width: u32, height: u32, depth: u32) -> Self {
        let count = width as usize * height as usize * depth as usize;
        // SAFETY: forwarded to the caller.
        Buffer3d { elements: unsafe { Elements::new(ptr.cast_mut(), count) }, size: UVec3::new(width, height, depth) }
    }

    /// Width, height and depth in elements.
    ///
    /// Program kinds: all.
    pub fn size(&self) -> UVec3 {
        self.size
    }

    /// The element at `idx`; out of bounds (in any axis), raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns all-zero words.
    ///
    /// Program kinds: all.
    pub fn load(&self, idx: UVec3) -> T {
        self.elements.load(index_3d(idx, self.size))
    }
}

impl<T: RtData> Index<UVec3> for Buffer3d<T> {
    type Output = T;

    /// `buffer[idx]`: the element at `idx`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns the zeroed sink.
    ///
    /// Program kinds: all.
    fn index(&self, idx: UVec3) -> &T {
        self.elements.get(index_3d(idx, self.size))
    }
}

impl<T: RtData> fmt::Debug for Buffer3d<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Buffer3d").field("element", &T::LAYOUT.rust).field("size", &self.size).finish()
    }
}

/// A read-write 3D buffer of `T` (OptiX's `rtBuffer<T, 3>`), indexed by
/// `UVec3` as [`Buffer3d`].
///
/// See the [module docs](self) for bounds checks and concurrency.
#[doc(alias = "rtBuffer")]
pub struct RwBuffer3d<T: RtData> {
    elements: Elements<T>,
    size: UVec3,
}

handle_traits!(RwBuffer3d);

impl<T: RtData> RwBuffer3d<T> {
    /// A handle to the `width * height * depth` elements at `ptr`. Host
    /// side only: the runtime creates handles, programs receive them as
    /// variables.
    ///
    /// # Safety
    /// As [`RwBuffer::from_raw_parts`] with `len = width * height * depth`:
    /// `ptr` points to that many elements and the sink after them.
    pub unsafe fn from_raw_parts(ptr: *mut T, width: u32, height: u32, depth: u32) -> Self {
        let count = width as usize * height as usize * depth as usize;
        // SAFETY: forwarded to the caller.
        RwBuffer3d { elements: unsafe { Elements::new(ptr, count) }, size: UVec3::new(width, height, depth) }
    }

    /// Width, height and depth in elements.
    ///
    /// Program kinds: all.
    pub fn size(&self) -> UVec3 {
        self.size
    }

    /// The element at `idx`; out of bounds (in any axis), raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns all-zero words.
    ///
    /// Program kinds: all.
    pub fn load(&self, idx: UVec3) -> T {
        self.elements.load(index_3d(idx, self.size))
    }

    /// Writes `v` at `idx`; out of bounds (in any axis), raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and writes nothing.
    ///
    /// Program kinds: all.
    pub fn store(&self, idx: UVec3, v: T) {
        self.elements.store(index_3d(idx, self.size), v)
    }
}

impl<T: RtData> Index<UVec3> for RwBuffer3d<T> {
    type Output = T;

    /// `buffer[idx]`: the element at `idx`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns the zeroed sink.
    ///
    /// Program kinds: all.
    fn index(&self, idx: UVec3) -> &T {
        self.elements.get(index_3d(idx, self.size))
    }
}

impl<T: RtData> IndexMut<UVec3> for RwBuffer3d<T> {
    /// `buffer[idx] = v`: the element at `idx`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`] and returns the zeroed sink,
    /// so the write is lost.
    ///
    /// Program kinds: all.
    fn index_mut(&mut self, idx: UVec3) -> &mut T {
        self.elements.get_mut(index_3d(idx, self.size))
    }
}

impl<T: RtData> fmt::Debug for RwBuffer3d<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("RwBuffer3d").field("element", &T::LAYOUT.rust).field("size", &self.size).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cpu::{ExecutionContext, with_context};
    use glam::Vec3;

    /// Storage with a sentinel around the elements, to see that nothing
    /// outside `[elements..., sink]` is touched.
    fn guarded(values: &[Vec3]) -> Vec<Vec3> {
        let mut v = vec![Vec3::splat(-7.0)];
        v.extend_from_slice(values);
        v.push(Vec3::splat(99.0)); // sink, garbage on purpose
        v.push(Vec3::splat(-7.0));
        v
    }

    #[test]
    fn in_bounds_accesses_raise_nothing() {
        let mut storage = guarded(&[Vec3::X, Vec3::Y, Vec3::Z]);
        let ((), ctx) = with_context(ExecutionContext::default(), || {
            let mut buf = unsafe { RwBuffer::from_raw_parts(storage.as_mut_ptr().add(1), 3) };
            assert_eq!(buf.len(), 3);
            assert!(!buf.is_empty());
            assert_eq!(buf.load(1), Vec3::Y);
            buf.store(2, Vec3::ONE);
            buf[0] = Vec3::splat(2.0);
            assert_eq!(buf[2], Vec3::ONE);
        });
        assert_eq!(ctx.pending_exception, None);
        assert_eq!(&storage[1..4], &[Vec3::splat(2.0), Vec3::Y, Vec3::ONE]);
    }

    #[test]
    fn out_of_bounds_1d_raises_and_stays_inside() {
        let mut storage = guarded(&[Vec3::X, Vec3::Y]);
        let before = storage.clone();
        let (loaded, ctx) = with_context(ExecutionContext::default(), || {
            let buf = unsafe { RwBuffer::from_raw_parts(storage.as_mut_ptr().add(1), 2) };
            buf.store(2, Vec3::splat(5.0));
            buf.store(u32::MAX, Vec3::splat(5.0));
            buf.load(2)
        });
        assert_eq!(loaded, Vec3::ZERO);
        assert_eq!(ctx.pending_exception, Some(EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS));
        assert_eq!(storage, before, "out-of-bounds stores must be dropped");

        // Index and IndexMut go to the zeroed sink, nowhere else.
        let ((), ctx) = with_context(ExecutionContext::default(), || {
            let mut buf = unsafe { RwBuffer::from_raw_parts(storage.as_mut_ptr().add(1), 2) };
            assert_eq!(buf[7], Vec3::ZERO);
            buf[3] += Vec3::ONE;
            assert_eq!(buf[3], Vec3::ZERO, "each out-of-bounds reference starts zeroed");
            let ro = unsafe { Buffer::from_raw_parts(storage.as_mut_ptr().add(1).cast_const(), 2) };
            assert_eq!(ro[2], Vec3::ZERO);
            assert_eq!(ro.load(9), Vec3::ZERO);
        });
        assert_eq!(ctx.pending_exception, Some(EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS));
        assert_eq!(&storage[..3], &before[..3]);
        assert_eq!(storage[4], before[4], "the element after the sink is untouched");
    }

    #[test]
    fn out_of_bounds_2d_checks_each_axis() {
        // 3x2, row-major: (x, y) at x + 3y.
        let values: Vec<Vec3> = (0..6).map(|i| Vec3::splat(i as f32)).collect();
        let mut storage = guarded(&values);
        let before = storage.clone();
        let (r, ctx) = with_context(ExecutionContext::default(), || {
            let buf = unsafe { RwBuffer2d::from_raw_parts(storage.as_mut_ptr().add(1), 3, 2) };
            assert_eq!(buf.size(), UVec2::new(3, 2));
            let in_bounds = buf.load(UVec2::new(2, 1));
            // x = 3 would alias (0, 1) in a linear check; it must not.
            let past_row = buf.load(UVec2::new(3, 0));
            buf.store(UVec2::new(3, 0), Vec3::splat(42.0));
            buf.store(UVec2::new(0, 2), Vec3::splat(42.0));
            (in_bounds, past_row)
        });
        assert_eq!(r, (Vec3::splat(5.0), Vec3::ZERO));
        assert_eq!(ctx.pending_exception, Some(EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS));
        assert_eq!(storage, before);

        let ((), ctx) = with_context(ExecutionContext::default(), || {
            let mut buf = unsafe { RwBuffer2d::from_raw_parts(storage.as_mut_ptr().add(1), 3, 2) };
            buf[UVec2::new(1, 1)] = Vec3::splat(-1.0);
            let ro = unsafe { Buffer2d::from_raw_parts(storage.as_mut_ptr().add(1).cast_const(), 3, 2) };
            assert_eq!(ro[UVec2::new(1, 1)], Vec3::splat(-1.0));
            assert_eq!(ro.load(UVec2::new(0, 1)), Vec3::splat(3.0));
        });
        assert_eq!(ctx.pending_exception, None);
        assert_eq!(storage[1 + 4], Vec3::splat(-1.0));
    }

    #[test]
    fn first_exception_wins() {
        let mut storage = guarded(&[Vec3::X]);
        let ((), ctx) = with_context(ExecutionContext::default(), || {
            cpu::raise(0x401);
            let buf = unsafe { RwBuffer::from_raw_parts(storage.as_mut_ptr().add(1), 1) };
            buf.store(1, Vec3::ONE);
        });
        assert_eq!(ctx.pending_exception, Some(0x401));
    }
}
