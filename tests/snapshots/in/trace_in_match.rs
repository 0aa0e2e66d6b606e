//! Traces inside `match` arms, with the resumable form's `switch` over the
//! scrutinee kept in the frame: a closest-hit program that picks its
//! bounce by material kind (one arm traces, one binds the kind, one
//! returns), and a ray generation program whose loop traces in one arm
//! and leaves the loop from another. And a helper that returns a block
//! ending in a trace's result (resumable: the block's statements run last).
use rt_std::prelude::*;

#[rt_payload]
pub struct Shade {
    pub color: Vec3,
    pub depth: u32,
}

/// What is straight above `p`.
#[rt_function]
pub fn seen_above(top_object: Object, p: Vec3, depth: u32) -> Vec3 {
    let mut up = Shade { color: Vec3::ZERO, depth: depth + 1 };
    {
        let r = Ray::new(p, vec3(0.0, 1.0, 0.0), 0, 0.001, f32::INFINITY);
        rt_trace(top_object, r, &mut up);
        up.color * 0.5
    }
}

#[rt_program(closest_hit)]
pub fn by_kind(prd: &mut Shade, #[var] kind: u32, #[var] top_object: Object, #[var] tint: Vec3) {
    let ray = current_ray();
    let p = ray.origin + t_hit() * ray.direction;
    let mut next = Shade { color: Vec3::ZERO, depth: prd.depth + 1 };
    match kind {
        0 => {
            let d = vec3(ray.direction.x, -ray.direction.y, ray.direction.z);
            rt_trace(top_object, Ray::new(p, d, 0, 0.001, f32::INFINITY), &mut next);
            prd.color = next.color * tint;
        }
        1 | 2 => rt_trace(top_object, Ray::new(p, ray.direction, 0, 0.001, f32::INFINITY), &mut next),
        k => {
            prd.color = tint * k as f32;
            return;
        }
    }
    prd.color += next.color * 0.5 + seen_above(top_object, p, prd.depth);
}

#[rt_program(ray_generation)]
pub fn match_camera(#[var] top_object: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] plan: Buffer<i32>) {
    let idx = launch_index();
    let mut total = Vec3::ZERO;
    let mut step = 0u32;
    loop {
        let mut prd = Shade { color: Vec3::ZERO, depth: 0 };
        match plan[step] {
            -1 => break,
            0 => {}
            n => {
                let o = vec3(idx.x as f32, idx.y as f32, n as f32);
                rt_trace(top_object, Ray::new(o, vec3(0.0, 0.0, -1.0), 0, 0.0, f32::INFINITY), &mut prd);
                total += prd.color;
            }
        }
        step += 1;
        if step >= 4 {
            break;
        }
    }
    out[idx] = total.extend(1.0);
}
