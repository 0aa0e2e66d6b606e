//! Exception kinds turned off (`Context::set_exception_enabled`, OptiX's
//! `rtContextSetExceptionEnabled`): the check still guards its operation
//! and the program goes on as it would with the kind on, but nothing is
//! raised, the exception program does not run and the launch reports no
//! record; each kind alone, and all. The same on every target.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

#[rt_payload]
pub struct Count {
    pub n: u32,
}

/// Launch index 0 reads past a buffer's end, 1 throws, 2 traces a NaN ray,
/// 3 recurses past the trace depth, 4 reads through a null bindless id, 5
/// samples through a null bindless sampler id, 6 does none of these. Word
/// `2 i` is
/// what the program saw, word `2 i + 1` the exception program's mark.
#[rt_program(ray_generation)]
pub fn probe(#[var] top: Object, #[var] table: Buffer<u32>, #[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    let mut seen = 1u32;
    if i == 0 {
        seen = 100 + table[table.len() + 3];
    } else if i == 1 {
        rt_throw(EXCEPTION_USER + 5);
        seen = 2;
    } else if i == 2 {
        let mut prd = Count { n: 40 };
        rt_trace(top, Ray::new(vec3(f32::NAN, 0.0, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, 100.0), &mut prd);
        seen = prd.n;
    } else if i == 3 {
        let mut prd = Count { n: 0 };
        rt_trace(top, Ray::new(vec3(0.2, 0.1, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, 100.0), &mut prd);
        seen = 1000 + prd.n;
    } else if i == 4 {
        seen = 2000 + BindlessBuffer::<u32>::NONE.load(0) + BindlessBuffer::<u32>::NONE.len();
    } else if i == 5 {
        let tex = BindlessSampler::<Sampler2d>::NONE;
        seen = 3000 + tex.size().x + tex.levels() * 10 + tex.sample(vec2(0.5, 0.5)).w as u32;
    }
    out[2 * i] = seen;
}

/// Traces the same ray again, without end.
#[rt_program(closest_hit)]
pub fn again(prd: &mut Count, #[var] top: Object) {
    prd.n += 1;
    let r = current_ray();
    let mut inner = Count { n: prd.n };
    rt_trace(top, Ray::new(r.origin, r.direction, 0, 0.0, 100.0), &mut inner);
    prd.n = inner.n;
}

#[rt_program(miss)]
pub fn missed(prd: &mut Count) {
    prd.n += 500;
}

#[rt_program(exception)]
pub fn mark(#[var] mut out: RwBuffer<u32>) {
    out[2 * launch_index().x + 1] = exception_code();
}

/// The launch with `off` turned off: the words and the records' (index, code).
fn run(on: On, off: &[ExceptionKind]) -> (Vec<u32>, Vec<(u32, u32)>) {
    let mut ctx = on.context();
    ctx.set_max_trace_depth(3);
    for kind in off {
        ctx.set_exception_enabled(*kind, false);
        assert!(!ctx.exception_enabled(*kind));
    }
    let quad = rt_tests::meshes::unit_quad();
    let g = ctx.create_triangles(quad).unwrap();
    let m = ctx.create_material();
    let ch = ctx.create_program(&again::PROGRAM);
    ctx.set_closest_hit_program(m, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
    let top = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let table = ctx.create_buffer::<u32>(BufferType::Input, vec![7, 8, 9]);
    ctx.set_var(Scope::Context, "table", table).unwrap();
    let out = ctx.create_buffer::<u32>(BufferType::InputOutput, vec![0; 14]);
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&probe::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&missed::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let ex = ctx.create_program(&mark::PROGRAM);
    ctx.set_exception_program(0, ex).unwrap();
    let report = ctx.launch_1d(0, 7).unwrap();
    let records = report.exceptions.iter().map(|e| (e.launch_index.x, e.code)).collect();
    (ctx.read_buffer::<u32>(out).unwrap(), records)
}

#[test]
fn a_kind_turned_off_raises_nothing_and_its_operation_stays_guarded() {
    let all = [
        (0, EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS, ExceptionKind::BufferIndexOutOfBounds),
        (1, EXCEPTION_USER + 5, ExceptionKind::User),
        (2, EXCEPTION_INVALID_RAY, ExceptionKind::InvalidRay),
        (3, EXCEPTION_TRACE_DEPTH_EXCEEDED, ExceptionKind::TraceDepthExceeded),
        (4, EXCEPTION_BUFFER_ID_INVALID, ExceptionKind::BufferIdInvalid),
        (5, EXCEPTION_TEXTURE_ID_INVALID, ExceptionKind::TextureIdInvalid),
    ];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let name = on.name();
        let (words, records) = run(on, &[]);
        assert_eq!(records, all.iter().map(|(i, code, _)| (*i, *code)).collect::<Vec<_>>(), "{name}");
        for (i, code, _) in all {
            assert_eq!(words[2 * i as usize + 1], code, "{name}: index {i} marked by the exception program");
        }
        // What each program saw: the read's guarded value, the program
        // going on after its throw, the NaN ray not traced (its miss did
        // not run), three closest hits before the depth limit.
        let seen = [words[0], words[2], words[4], words[6], words[8], words[10], words[12]];
        // A null sampler id: size 0, one level, a zero sample.
        assert_eq!(seen[1..], [2, 40, 1003, 2000, 3010, 1], "{name}");
        assert_eq!(seen[0], run(On::CPU, &[]).0[0], "{name}: the guarded read agrees with the CPU backend's");
        for (i, _, kind) in all {
            let (w, r) = run(on, &[kind]);
            let expected: Vec<(u32, u32)> = all.iter().filter(|(j, ..)| *j != i).map(|(j, c, _)| (*j, *c)).collect();
            assert_eq!(r, expected, "{name}: {kind:?} off");
            assert_eq!(w[2 * i as usize + 1], 0, "{name}: {kind:?} off, no exception program at {i}");
            assert_eq!(
                [w[0], w[2], w[4], w[6], w[8], w[10], w[12]],
                seen,
                "{name}: {kind:?} off, the programs saw the same"
            );
        }
        let (w, r) = run(on, &[ExceptionKind::All]);
        assert!(r.is_empty(), "{name}: {r:?}");
        assert!(w.iter().skip(1).step_by(2).all(|&m| m == 0), "{name}");
        assert_eq!([w[0], w[2], w[4], w[6], w[8], w[10], w[12]], seen, "{name}");
    }
}
