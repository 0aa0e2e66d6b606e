//! Bindless buffers: a buffer's id as a value a program holds and reads
//! through (OptiX's `rtBufferId<T, 1>`, `rtBufferGetId`).
//!
//! A [`BindlessBuffer<T>`] is one `u32` word, the id of a buffer of `T`:
//! a program may hold it in a `#[var]` variable, a buffer element (a
//! buffer of ids: per-mesh data chosen by an index), a struct or payload
//! field, compare it with `==`, and read the buffer through it as through a
//! [`Buffer<T>`](crate::Buffer): `ids.load(i)`, `ids[i]`, `ids.len()`.
//! [`RwBindlessBuffer<T>`] also writes (`store`), and names only buffers
//! that programs may write.
//!
//! The host gets a buffer's id with `Context::buffer_id::<T>(buffer)` (or
//! `rw_buffer_id`), which checks the buffer's element type, and sets it
//! like any value; a launch checks every id variable against the buffer it
//! names. A program may make ids too: [`BindlessBuffer::NONE`],
//! [`BindlessBuffer::default()`] and [`BindlessBuffer::from_id`].
//!
//! Every access through an id checks it: an id that names no buffer of the
//! launch (zero, [`NONE`](BindlessBuffer::NONE), an id from elsewhere), a
//! buffer of another element type, or (for [`RwBindlessBuffer`]) a buffer
//! programs may not write raises
//! [`EXCEPTION_BUFFER_ID_INVALID`](crate::EXCEPTION_BUFFER_ID_INVALID): a
//! load returns zero, a store is dropped, `len` is 0. An index out of
//! bounds of the named buffer raises
//! [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`](crate::EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS)
//! as through a bound buffer. Ids are the context's buffer handles plus
//! one, so zero is none; a two-dimensional buffer reads as its
//! `width * height` elements row by row. A bounding-box program runs at
//! build time, outside any launch, and reads no buffer through an id (the
//! compiler refuses it).

use core::fmt;
use core::marker::PhantomData;
use core::ops::Index;

use crate::buffer::{Buffer, RwBuffer};
use crate::data::{RtData, zeroed};
use crate::program::{LayoutKind, TypeLayout};

/// The layout every `BindlessBuffer<T>` shares (one word): its element type
/// is checked against the buffer an id names at launch and at each access.
pub const BINDLESS_LAYOUT: TypeLayout = TypeLayout {
    kind: LayoutKind::BufferId { writable: false, element: None },
    rust: "BindlessBuffer",
    wgsl: "u32",
    words: 1,
    fields: &[],
};

/// The layout every `RwBindlessBuffer<T>` shares.
pub const RW_BINDLESS_LAYOUT: TypeLayout = TypeLayout {
    kind: LayoutKind::BufferId { writable: true, element: None },
    rust: "RwBindlessBuffer",
    wgsl: "u32",
    words: 1,
    fields: &[],
};

/// Raises the invalid-id exception.
fn invalid() {
    crate::cpu::raise(crate::EXCEPTION_BUFFER_ID_INVALID);
}

/// A zero `T` that lives as long as the program: what `ids[i]` refers to
/// through an invalid id (one per element type, made once).
fn zero_ref<T: RtData + Send + Sync>() -> &'static T {
    use std::any::{Any, TypeId};
    use std::sync::Mutex;
    type Zeros = Vec<(TypeId, &'static (dyn Any + Send + Sync))>;
    static ZEROS: Mutex<Zeros> = Mutex::new(Vec::new());
    let mut zeros = ZEROS.lock().unwrap_or_else(|e| e.into_inner());
    let id = TypeId::of::<T>();
    let z = match zeros.iter().find(|(t, _)| *t == id) {
        Some((_, z)) => *z,
        None => {
            let z: &'static (dyn Any + Send + Sync) = Box::leak(Box::new(zeroed::<T>()));
            zeros.push((id, z));
            z
        }
    };
    z.downcast_ref::<T>().expect("stored under its own TypeId")
}

macro_rules! id_common {
    ($name:ident, $layout:ident, $what:literal) => {
        impl<T> $name<T> {
            #[doc = concat!("No buffer: reading through it raises [`EXCEPTION_BUFFER_ID_INVALID`](crate::EXCEPTION_BUFFER_ID_INVALID).")]
            pub const NONE: Self = Self::from_id(0);

            /// The buffer of id `id` (as `Context::buffer_id` gives it, or
            /// read from a buffer of ids). Nothing is checked until an
            /// access.
            pub const fn from_id(id: u32) -> Self {
                $name { id, element: PhantomData }
            }

            /// The id.
            pub const fn id(self) -> u32 {
                self.id
            }
        }

        impl<T> Clone for $name<T> {
            fn clone(&self) -> Self {
                *self
            }
        }

        impl<T> Copy for $name<T> {}

        impl<T> PartialEq for $name<T> {
            fn eq(&self, other: &Self) -> bool {
                self.id == other.id
            }
        }

        impl<T> Eq for $name<T> {}

        impl<T> Default for $name<T> {
            fn default() -> Self {
                Self::NONE
            }
        }

        impl<T> fmt::Debug for $name<T> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, concat!($what, "({})"), self.id)
            }
        }

        impl<T: 'static> RtData for $name<T> {
            const LAYOUT: TypeLayout = $layout;

            fn write_words(&self, out: &mut [u32]) {
                out[0] = self.id;
            }

            fn read_words(words: &[u32]) -> Self {
                Self::from_id(words[0])
            }
        }
    };
}

/// The id of a read-only buffer of `T`: one `u32` word, 0 for none. Read
/// through it as through a [`Buffer<T>`](crate::Buffer); see the [module
/// docs](self).
///
/// Program kinds: all but bounding_box.
#[doc(alias = "rtBufferId")]
#[repr(transparent)]
pub struct BindlessBuffer<T> {
    id: u32,
    element: PhantomData<fn() -> T>,
}

id_common!(BindlessBuffer, BINDLESS_LAYOUT, "BindlessBuffer");

impl<T: RtData> BindlessBuffer<T> {
    /// The buffer the id names, or `None` after raising the invalid-id
    /// exception.
    fn buffer(self) -> Option<Buffer<T>> {
        let b = crate::cpu::bindless_buffer::<Buffer<T>>(self.id, false);
        if b.is_none() {
            invalid();
        }
        b
    }

    /// Number of elements; 0 through an invalid id (after the exception).
    ///
    /// Program kinds: all but bounding_box.
    pub fn len(self) -> u32 {
        self.buffer().map_or(0, |b| b.len())
    }

    /// Whether the buffer has no elements (true through an invalid id).
    ///
    /// Program kinds: all but bounding_box.
    pub fn is_empty(self) -> bool {
        self.len() == 0
    }

    /// The element at `i`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`](crate::EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS),
    /// through an invalid id
    /// [`EXCEPTION_BUFFER_ID_INVALID`](crate::EXCEPTION_BUFFER_ID_INVALID);
    /// either way returns all-zero words.
    ///
    /// Program kinds: all but bounding_box.
    pub fn load(self, i: u32) -> T {
        self.buffer().map_or_else(zeroed, |b| b.load(i))
    }
}

impl<T: RtData + Send + Sync> Index<u32> for BindlessBuffer<T> {
    type Output = T;

    /// `ids[i]`: as [`load`](BindlessBuffer::load).
    ///
    /// Program kinds: all but bounding_box.
    fn index(&self, i: u32) -> &T {
        match self.buffer() {
            Some(b) => b.element_ref(i),
            None => zero_ref(),
        }
    }
}

/// The id of a buffer of `T` that programs may write (`Output` or
/// `InputOutput`): one `u32` word, 0 for none. Read and written through
/// it as through an [`RwBuffer<T>`](crate::RwBuffer); see the [module
/// docs](self).
///
/// Program kinds: all but bounding_box.
#[doc(alias = "rtBufferId")]
#[repr(transparent)]
pub struct RwBindlessBuffer<T> {
    id: u32,
    element: PhantomData<fn() -> T>,
}

id_common!(RwBindlessBuffer, RW_BINDLESS_LAYOUT, "RwBindlessBuffer");

impl<T: RtData> RwBindlessBuffer<T> {
    /// The buffer the id names, or `None` after raising the invalid-id
    /// exception.
    fn buffer(self) -> Option<RwBuffer<T>> {
        let b = crate::cpu::bindless_buffer::<RwBuffer<T>>(self.id, true);
        if b.is_none() {
            invalid();
        }
        b
    }

    /// Number of elements; 0 through an invalid id (after the exception).
    ///
    /// Program kinds: all but bounding_box.
    pub fn len(self) -> u32 {
        self.buffer().map_or(0, |b| b.len())
    }

    /// Whether the buffer has no elements (true through an invalid id).
    ///
    /// Program kinds: all but bounding_box.
    pub fn is_empty(self) -> bool {
        self.len() == 0
    }

    /// The element at `i`, as [`BindlessBuffer::load`].
    ///
    /// Program kinds: all but bounding_box.
    pub fn load(self, i: u32) -> T {
        self.buffer().map_or_else(zeroed, |b| b.load(i))
    }

    /// Writes `v` at `i`; out of bounds, raises
    /// [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`](crate::EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS),
    /// through an invalid id
    /// [`EXCEPTION_BUFFER_ID_INVALID`](crate::EXCEPTION_BUFFER_ID_INVALID);
    /// either way writes nothing.
    ///
    /// Program kinds: all but bounding_box.
    pub fn store(self, i: u32, v: T) {
        if let Some(b) = self.buffer() {
            b.store(i, v)
        }
    }

    /// The same buffer, read-only (an id of the same buffer).
    ///
    /// Program kinds: all but bounding_box.
    pub const fn read_only(self) -> BindlessBuffer<T> {
        BindlessBuffer::from_id(self.id)
    }
}

impl<T: RtData + Send + Sync> Index<u32> for RwBindlessBuffer<T> {
    type Output = T;

    /// `ids[i]`: as [`load`](RwBindlessBuffer::load). Writes go through
    /// [`store`](RwBindlessBuffer::store).
    ///
    /// Program kinds: all but bounding_box.
    fn index(&self, i: u32) -> &T {
        match self.buffer() {
            Some(b) => b.element_ref(i),
            None => zero_ref(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cpu::{AnyAttributes, ExecutionContext, Tracer, with_context, with_tracer};
    use crate::{EXCEPTION_BUFFER_ID_INVALID, EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS, Object, Ray};
    use std::any::Any;

    /// Id 1 names `read` (and `write`, if any): as the CPU backend's lane.
    struct OneBuffer {
        read: Box<dyn Any + Send + Sync>,
        write: Option<Box<dyn Any + Send + Sync>>,
    }

    impl Tracer for OneBuffer {
        fn trace(&self, _: Object, _: &Ray, _: &mut dyn Any, _: u32, _: u32, _: f32) {}
        fn potential_intersection(&self, _: f32) -> bool {
            false
        }
        fn report_intersection(&self, _: u32, _: Option<&dyn AnyAttributes>) -> bool {
            false
        }
        fn print(&self, _: &str) {}
        fn buffer(&self, id: u32, writable: bool) -> Option<&(dyn Any + Send + Sync)> {
            match (id, writable) {
                (1, false) => Some(&*self.read),
                (1, true) => self.write.as_deref(),
                _ => None,
            }
        }
    }

    #[test]
    fn reads_and_writes_go_through_the_tracers_handles() {
        // Three elements and the sink.
        let mut storage = vec![4u32, 5, 6, 99];
        let ptr = storage.as_mut_ptr();
        // SAFETY: four elements, the last the sink; they outlive the tracer.
        let tracer = unsafe {
            OneBuffer {
                read: Box::new(Buffer::from_raw_parts(ptr.cast_const(), 3)),
                write: Some(Box::new(RwBuffer::from_raw_parts(ptr, 3))),
            }
        };
        let (got, ctx) = with_tracer(ExecutionContext::default(), &tracer, || {
            let b = BindlessBuffer::<u32>::from_id(1);
            let w = RwBindlessBuffer::<u32>::from_id(1);
            w.store(0, 40);
            (b.len(), b.load(0), b[2], w.read_only() == b)
        });
        assert_eq!(got, (3, 40, 6, true));
        assert_eq!(ctx.pending_exception, None);
        let (got, ctx) =
            with_tracer(ExecutionContext::default(), &tracer, || BindlessBuffer::<u32>::from_id(1).load(3));
        assert_eq!((got, ctx.pending_exception), (0, Some(EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS)));
        // Another element type, another id, none: invalid.
        for read in [
            || BindlessBuffer::<f32>::from_id(1).load(0).to_bits(),
            || BindlessBuffer::<u32>::from_id(2)[0],
            || BindlessBuffer::<u32>::NONE.len(),
        ] {
            let (got, ctx) = with_tracer(ExecutionContext::default(), &tracer, read);
            assert_eq!((got, ctx.pending_exception), (0, Some(EXCEPTION_BUFFER_ID_INVALID)));
        }
        // Without a tracer (no launch), every id is invalid.
        let (got, ctx) = with_context(ExecutionContext::default(), || BindlessBuffer::<u32>::from_id(1).load(0));
        assert_eq!((got, ctx.pending_exception), (0, Some(EXCEPTION_BUFFER_ID_INVALID)));
        // A writable id of a buffer programs may not write: the store is dropped.
        let read_only = OneBuffer { read: tracer.read, write: None };
        let ((), ctx) =
            with_tracer(ExecutionContext::default(), &read_only, || RwBindlessBuffer::<u32>::from_id(1).store(1, 7));
        assert_eq!(ctx.pending_exception, Some(EXCEPTION_BUFFER_ID_INVALID));
        assert_eq!(storage, vec![40, 5, 6, 99]);
    }
}
