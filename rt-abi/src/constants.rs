//! The values of rt-std's ray flags, visibility mask and exception codes.
//! rt-std re-exports them (with their docs), the compiler folds them into
//! WGSL literals and the runtime's backends test against them.

/// No flags.
pub const RAY_FLAG_NONE: u32 = 0;
/// End the search at the first accepted intersection.
pub const RAY_FLAG_TERMINATE_ON_FIRST_HIT: u32 = 1;
/// Skip any-hit programs.
pub const RAY_FLAG_DISABLE_ANYHIT: u32 = 2;
/// Skip the closest-hit program of the committed intersection.
pub const RAY_FLAG_DISABLE_CLOSESTHIT: u32 = 4;
/// Ignore triangles whose back faces the ray.
pub const RAY_FLAG_CULL_BACK_FACING: u32 = 8;
/// Ignore triangles whose front faces the ray.
pub const RAY_FLAG_CULL_FRONT_FACING: u32 = 16;
/// Every bit of an instance's 8-bit visibility mask.
pub const RAY_MASK_ALL: u32 = 0xFF;
/// The instance id of an instance no id was set on
/// (`Context::set_instance_id`): what `instance_id()` returns then, and the
/// value that clears an id.
pub const INSTANCE_ID_NONE: u32 = u32::MAX;

/// `rt_trace` at the context's maximum trace depth. OptiX's code,
/// `RT_EXCEPTION_TRACE_DEPTH_EXCEEDED`.
pub const EXCEPTION_TRACE_DEPTH_EXCEEDED: u32 = 0x3ED;
/// A buffer accessed outside its bounds. OptiX's code,
/// `RT_EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`.
pub const EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS: u32 = 0x3FD;
/// `rt_trace` given a NaN or infinite ray. OptiX's code,
/// `RT_EXCEPTION_INVALID_RAY`.
pub const EXCEPTION_INVALID_RAY: u32 = 0x3FE;
/// Integer overflow (`+ - *`, negation, `abs`, shifts by 32 or more,
/// `MIN / -1`): raised only on the CPU backend with
/// integer exceptions on (`Context::set_integer_exceptions`).
pub const EXCEPTION_INTEGER_OVERFLOW: u32 = 0x3F1;
/// Integer division or remainder by zero: as
/// [`EXCEPTION_INTEGER_OVERFLOW`], on request, on the CPU backend.
pub const EXCEPTION_INTEGER_DIVIDE_BY_ZERO: u32 = 0x3F2;
/// A callable program called through an id that names no callable program
/// of the call's signature (zero, a stale id, or a callable of another
/// signature): the call returns the zero value of its result. OptiX's
/// code, `RT_EXCEPTION_PROGRAM_ID_INVALID`.
pub const EXCEPTION_PROGRAM_ID_INVALID: u32 = 0x3EE;
/// A buffer read or written through a bindless buffer id that names no
/// buffer of the launch (zero, an id the context did not give), a buffer of
/// another element type, or, for a writable id, a buffer programs may not
/// write: a load returns zero, a store is dropped. OptiX's code,
/// `RT_EXCEPTION_BUFFER_ID_INVALID`.
pub const EXCEPTION_BUFFER_ID_INVALID: u32 = 0x3FA;
/// A texture sampled through a bindless sampler id that names no sampler
/// of the launch (zero, an id the context did not give) or a sampler of
/// another shape (a cube map read as a 2D sampler): the sample is zero, the
/// size 0. OptiX's code, `RT_EXCEPTION_TEXTURE_ID_INVALID`.
pub const EXCEPTION_TEXTURE_ID_INVALID: u32 = 0x3EF;
/// A program's panic: `unwrap`/`expect` of a `None`. The program goes on
/// with the zero value, as after any exception, and the launch index's
/// work stops when it returns. Enabled with the programs' own codes
/// (`exception_kind_bit` gives it their bit).
pub const EXCEPTION_PANIC: u32 = 0x3F3;
/// The first code free for programs' own `rt_throw` codes.
pub const EXCEPTION_USER: u32 = 0x400;

/// The bit of exception `code`'s kind in a mask of enabled kinds (the
/// launch uniform's `exceptions`; `Context::set_exception_enabled`): one
/// per built-in code, and one for every other code (`rt_throw`'s).
pub const fn exception_kind_bit(code: u32) -> u32 {
    match code {
        EXCEPTION_TRACE_DEPTH_EXCEEDED => 1,
        EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS => 2,
        EXCEPTION_INVALID_RAY => 4,
        EXCEPTION_INTEGER_OVERFLOW => 8,
        EXCEPTION_INTEGER_DIVIDE_BY_ZERO => 16,
        EXCEPTION_PROGRAM_ID_INVALID => 64,
        EXCEPTION_BUFFER_ID_INVALID => 128,
        EXCEPTION_TEXTURE_ID_INVALID => 256,
        _ => 32,
    }
}

/// Every exception kind enabled.
pub const ALL_EXCEPTION_KINDS: u32 = 511;

/// Every constant above that programs may name, by its rt-std name.
pub const CONSTANTS: &[(&str, u32)] = &[
    ("RAY_FLAG_NONE", RAY_FLAG_NONE),
    ("RAY_FLAG_TERMINATE_ON_FIRST_HIT", RAY_FLAG_TERMINATE_ON_FIRST_HIT),
    ("RAY_FLAG_DISABLE_ANYHIT", RAY_FLAG_DISABLE_ANYHIT),
    ("RAY_FLAG_DISABLE_CLOSESTHIT", RAY_FLAG_DISABLE_CLOSESTHIT),
    ("RAY_FLAG_CULL_BACK_FACING", RAY_FLAG_CULL_BACK_FACING),
    ("RAY_FLAG_CULL_FRONT_FACING", RAY_FLAG_CULL_FRONT_FACING),
    ("RAY_MASK_ALL", RAY_MASK_ALL),
    ("INSTANCE_ID_NONE", INSTANCE_ID_NONE),
    ("EXCEPTION_TRACE_DEPTH_EXCEEDED", EXCEPTION_TRACE_DEPTH_EXCEEDED),
    ("EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS", EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS),
    ("EXCEPTION_INVALID_RAY", EXCEPTION_INVALID_RAY),
    ("EXCEPTION_INTEGER_OVERFLOW", EXCEPTION_INTEGER_OVERFLOW),
    ("EXCEPTION_INTEGER_DIVIDE_BY_ZERO", EXCEPTION_INTEGER_DIVIDE_BY_ZERO),
    ("EXCEPTION_PROGRAM_ID_INVALID", EXCEPTION_PROGRAM_ID_INVALID),
    ("EXCEPTION_BUFFER_ID_INVALID", EXCEPTION_BUFFER_ID_INVALID),
    ("EXCEPTION_TEXTURE_ID_INVALID", EXCEPTION_TEXTURE_ID_INVALID),
    ("EXCEPTION_PANIC", EXCEPTION_PANIC),
    ("EXCEPTION_USER", EXCEPTION_USER),
];

/// The value of the constant rt-std calls `name`.
pub fn constant(name: &str) -> Option<u32> {
    CONSTANTS.iter().find(|(n, _)| *n == name).map(|(_, v)| *v)
}
