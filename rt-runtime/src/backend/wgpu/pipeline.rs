//! The pipeline cache: one compute pipeline per megakernel WGSL, created
//! the first time a launch links that source, over the bind-group layout
//! of its traversal (`slots` TLASes: 0 for the compute traversal).

use super::device::Gpu;
use crate::error::{DeviceError, Result};

/// Makes `gpu` hold a pipeline for `wgsl` (printing the generator's
/// `warning` when it creates one); a kernel that does not compile is an
/// error naming `RT_DUMP_WGSL`.
pub(crate) async fn ensure(gpu: &mut Gpu, wgsl: &str, slots: u32, warning: Option<&str>) -> Result<()> {
    if gpu.pipelines.contains_key(wgsl) {
        return Ok(());
    }
    if let Some(w) = warning {
        eprintln!("{w}");
    }
    let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = gpu.device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("rt megakernel"),
        source: wgpu::ShaderSource::Wgsl(wgsl.to_string().into()),
    });
    let layout = gpu.layout_for(slots).clone();
    let pipeline_layout = gpu.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("rt megakernel"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = gpu.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("rt megakernel"),
        layout: Some(&pipeline_layout),
        module: &module,
        entry_point: Some("rt_main"),
        compilation_options: Default::default(),
        cache: None,
    });
    if let Some(e) = scope.pop().await {
        return Err(DeviceError::Gpu(format!(
            "the linked megakernel does not compile (set RT_DUMP_WGSL=1 to see it): {e}"
        ))
        .into());
    }
    gpu.pipelines.insert(wgsl.to_string(), pipeline);
    gpu.pipelines_created += 1;
    Ok(())
}
