//! Exceptions: a ray generation program that validates its inputs and
//! raises user exceptions with `rt_throw`, and an exception program that
//! matches on `exception_code()`, built-in codes included.
use rt_std::prelude::*;

/// First user code for this program's errors.
#[rt_const]
pub const ERR_BAD_SCALE: u32 = EXCEPTION_USER + 1;

#[rt_program(ray_generation)]
pub fn checked_fill(#[var] scale: f32, #[var] values: Buffer<f32>, #[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x + launch_index().y * launch_dim().x;
    if !scale.is_finite() || scale <= 0.0 {
        rt_throw(ERR_BAD_SCALE);
        return;
    }
    if i >= values.len() {
        rt_throw(EXCEPTION_USER);
        return;
    }
    out[i] = values[i] * scale;
}

#[rt_program(exception)]
pub fn report_exception(#[var] mut out_color: RwBuffer2d<Vec4>) {
    let code = exception_code();
    let color = match code {
        EXCEPTION_TRACE_DEPTH_EXCEEDED => vec3(1.0, 0.0, 0.0),
        EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS | EXCEPTION_INVALID_RAY => vec3(1.0, 1.0, 0.0),
        _ => {
            if code >= EXCEPTION_USER {
                rt_printf!("user exception {}", code - EXCEPTION_USER);
            }
            vec3(1.0, 0.0, 1.0)
        }
    };
    out_color[launch_index()] = color.extend(1.0);
}
