//! 3D buffers (OptiX's `rtBuffer<T, 3>`): `Buffer3d<T>` and `RwBuffer3d<T>`
//! from `Context::create_buffer_3d`, indexed by `UVec3` (x fastest, then y,
//! then z), their `size()`, and out-of-bounds indices raising the
//! buffer-index exception without touching another element (a `z` whose
//! linear offset wraps in 32 bits onto element 0 included), exact on every
//! target.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

const W: u32 = 3;
const H: u32 = 4;
const D: u32 = 5;

/// Launch index `(x, y + z * H)` copies `input[(x, y, z)]` into
/// `out[(x, y, z)]` with its coordinates; `bad` (a launch index) reads an
/// index past the depth and writes one past the width instead.
#[rt_program(ray_generation)]
pub fn copy_3d(
    #[var] input: Buffer3d<u32>,
    #[var] mut out: RwBuffer3d<u32>,
    #[var] mut sizes: RwBuffer<u32>,
    #[var] bad: UVec2,
) {
    let l = launch_index();
    let size = out.size();
    let at = uvec3(l.x, l.y % size.y, l.y / size.y);
    let mut read = at;
    if l == bad {
        // (0x40000000 * 4 + 0) * 3 wraps to 0: element (0, 0, 0) unless
        // the depth is checked.
        read = uvec3(0, 0, 0x40000000);
        out[uvec3(size.x, 0, 0)] = 1;
    }
    out[at] = input[read] * 1000 + at.x + 10 * at.y + 100 * at.z;
    if l == UVec2::ZERO {
        let s = input.size();
        sizes[0] = s.x;
        sizes[1] = s.y;
        sizes[2] = s.z;
        sizes[3] = size.x;
        sizes[4] = size.y;
        sizes[5] = size.z;
    }
}

fn run(on: On) -> (Vec<u32>, Vec<u32>, Vec<ExceptionRecord>) {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    let input = ctx.create_buffer_3d::<u32>(BufferType::Input, W, H, D).unwrap();
    ctx.write_buffer(input, &(0..W * H * D).map(|i| i + 7).collect::<Vec<_>>()).unwrap();
    let out = ctx.create_buffer_3d::<u32>(BufferType::Output, W, H, D).unwrap();
    assert_eq!(ctx.buffer_size_3d(out).unwrap(), (W, H, D));
    let sizes = ctx.create_buffer::<u32>(BufferType::Output, vec![0; 6]);
    ctx.set_var(Scope::Context, "input", input).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "sizes", sizes).unwrap();
    ctx.set_var(Scope::Context, "bad", UVec2::new(2, 3 + 4 * H)).unwrap();
    let rg = ctx.create_program(&copy_3d::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch(0, W, H * D).unwrap();
    (ctx.read_buffer(out).unwrap(), ctx.read_buffer(sizes).unwrap(), report.exceptions)
}

#[test]
fn three_d_buffers_index_by_uvec3_and_check_every_axis_on_every_target() {
    let mut expected = Vec::new();
    for z in 0..D {
        for y in 0..H {
            for x in 0..W {
                let i = x + (y + z * H) * W;
                let own = x + 10 * y + 100 * z;
                expected.push(if (x, y, z) == (2, 3, 4) { own } else { (i + 7) * 1000 + own });
            }
        }
    }
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let (out, sizes, exceptions) = run(on);
        assert_eq!(out, expected, "{}", on.name());
        assert_eq!(sizes, [W, H, D, W, H, D], "{}", on.name());
        let raised: Vec<(UVec2, u32)> = exceptions.iter().map(|e| (e.launch_index, e.code)).collect();
        assert_eq!(raised, [(UVec2::new(2, 3 + 4 * H), EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS)], "{}", on.name());
    }
}

#[test]
fn a_3d_buffer_too_large_for_32_bit_indices_is_refused_by_size() {
    let mut ctx = Context::new();
    let e = ctx.create_buffer_3d::<u32>(BufferType::Output, 2048, 2048, 1025).unwrap_err().to_string();
    assert!(e.contains("2048x2048x1025 elements do not fit in 32-bit indices"), "{e}");
}
