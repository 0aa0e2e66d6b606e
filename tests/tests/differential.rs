use rt_runtime::*;
use rt_std::prelude::*;
use rt_std::program::ProgramDescriptor;

#[rt_function]
pub fn twice(v: f32) -> f32 {
    v * 2.0
}

#[rt_payload]
pub struct Nothing { pub v: f32 }
#[rt_program(miss)]
pub fn dummy_miss(prd: &mut Nothing) { prd.v = 1.0; }

macro_rules! diff {
    ($name:ident ($a:ident : $ta:ident) -> [$r:ident; $n:tt] $body:block) => {
        mod $name {
            use super::*;
            #[rt_program(ray_generation)]
            pub fn $name(#[var] in0: Buffer<$ta>, #[var] out: RwBuffer<$r>, #[var] top: Object) {
                let idx = launch_index().x;
                if idx > 1000000 {
                    let mut prd = Nothing { v: 0.0 };
                    rt_trace(top, Ray::new(Vec3::ZERO, Vec3::Z, 0, 0.0, 1.0), &mut prd);
                }
                let $a = in0[idx];
                let res: [$r; $n] = $body;
                for k in 0..$n {
                    out.store(idx * $n + k, res[k as usize]);
                }
            }
            pub fn reference($a: $ta) -> [$r; $n] $body
        }
    };
}

diff!(p1(x: f32) -> [f32; 3] { [x + 1.0, x * 3.0, twice(x)] });
diff!(p2(x: f32) -> [f32; 3] { [x - 1.0, x * 5.0, twice(x) + 1.0] });
diff!(p3(x: f32) -> [f32; 3] { [x - 2.0, x * 7.0, twice(x) + 2.0] });
diff!(p4(x: f32) -> [f32; 3] { [x - 3.0, x * 9.0, twice(x) + 3.0] });

fn run(backend: Backend, descs: &[&'static ProgramDescriptor]) {
    let t = std::time::Instant::now();
    let mut ctx = Context::new();
    ctx.set_backend(backend);
    let m = ctx.create_program(&dummy_miss::PROGRAM);
    ctx.set_miss_program(0, m).unwrap();
    let gg = ctx.create_geometry_group(&[], Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    let xs: Vec<f32> = (0..256).map(|i| i as f32 * 0.37 - 40.0).collect();
    for d in descs {
        let p = ctx.create_program(d);
        let a = ctx.create_buffer(BufferType::Input, xs.clone());
        let o = ctx.create_buffer(BufferType::Output, vec![0f32; 256 * 3]);
        ctx.set_var(p, "in0", a).unwrap();
        ctx.set_var(p, "out", o).unwrap();
        ctx.set_ray_generation_program(0, p).unwrap();
        let t1 = std::time::Instant::now();
        let rep = ctx.launch(0, 256, 1).unwrap(); eprintln!("{:?}", rep.timings);
        let r = ctx.read_buffer::<f32>(o).unwrap();
        eprintln!("{backend:?} {} {:?} {:?}", d.name, t1.elapsed(), &r[..6]);
    }
    eprintln!("total {:?}", t.elapsed());
}

#[test]
fn proto() {
    let d = [&p1::p1::PROGRAM, &p2::p2::PROGRAM, &p3::p3::PROGRAM, &p4::p4::PROGRAM];
    run(Backend::Cpu, &d);
    run(Backend::Wgpu, &d);
    eprintln!("{:?}", p1::reference(2.0));
}
