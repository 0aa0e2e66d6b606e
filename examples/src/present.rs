//! Showing a launch's output in a window straight from the GPU: a wgpu
//! surface on the context's own device ([`Context::open_wgpu_for_surface`])
//! and a draw that reads the output buffer where the launch left it
//! ([`Context::wgpu_buffer`]), so no frame goes through the host. The
//! viewer uses it when the wgpu backend renders; the CPU backend's frames
//! go through softbuffer.
//!
//! The draw turns each pixel into the same 8-bit colour
//! [`rt_runtime::image_out::to_rgba8`] (and so `render`'s PNG) gives it:
//! clamped to [0, 1], times 255, plus a half, truncated; a NaN is 0. The
//! surface takes a linear 8-bit format, since the output is already
//! gamma corrected.

use rt_runtime::{BufferId, Context};
use std::sync::Arc;
use winit::window::Window;

/// A window's wgpu surface and the draw that fills it from a buffer.
pub struct GpuPresenter {
    surface: wgpu::Surface<'static>,
    device: wgpu::Device,
    queue: wgpu::Queue,
    config: wgpu::SurfaceConfiguration,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    /// The size of the picture the pixels are read from: the buffer's row
    /// stride, then the width and height shown.
    uniform: wgpu::Buffer,
    /// The last picture, copied from the launch's buffer (the context's
    /// heap moves between launches; this copy stays for redraws).
    picture: Option<(wgpu::Buffer, wgpu::BindGroup)>,
}

/// The draw: a triangle over the window; each pixel reads its element of
/// the picture, bottom row first as launch indices are.
const SHADER: &str = r"
struct Size { stride: u32, width: u32, height: u32, pad: u32 }
@group(0) @binding(0) var<storage, read> picture: array<vec4<f32>>;
@group(0) @binding(1) var<uniform> size: Size;

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let xy = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(xy * 2.0 - 1.0, 0.0, 1.0);
}

fn quantise(v: f32) -> f32 {
    let q = floor(clamp(v, 0.0, 1.0) * 255.0 + 0.5);
    return select(q, 0.0, v != v) / 255.0;
}

@fragment
fn fs(@builtin(position) at: vec4<f32>) -> @location(0) vec4<f32> {
    let x = u32(at.x);
    let y = u32(at.y);
    if x >= size.width || y >= size.height {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let c = picture[(size.height - 1u - y) * size.stride + x];
    return vec4<f32>(quantise(c.x), quantise(c.y), quantise(c.z), 1.0);
}
";

impl GpuPresenter {
    /// Opens `ctx`'s wgpu device on an adapter that presents to `window`
    /// (making wgpu its backend; call it before the first launch) and
    /// configures the window's surface at `size`. Fails, saying why, when
    /// the window has no wgpu surface or no linear 8-bit format.
    pub fn open(ctx: &mut Context, window: Arc<Window>, size: (u32, u32)) -> Result<GpuPresenter, String> {
        let instance = rt_runtime::backend::wgpu::instance();
        let surface = instance.create_surface(window).map_err(|e| format!("no wgpu surface for the window: {e}"))?;
        let gpu = ctx.open_wgpu_for_surface(&instance, &surface).map_err(|e| e.to_string())?;
        let adapter = gpu.adapter.as_ref().expect("the context opened the device");
        let caps = surface.get_capabilities(adapter);
        let format = [wgpu::TextureFormat::Bgra8Unorm, wgpu::TextureFormat::Rgba8Unorm]
            .into_iter()
            .find(|f| caps.formats.contains(f))
            .ok_or_else(|| format!("the window's surface has no linear 8-bit format (it has {:?})", caps.formats))?;
        let mut config = surface
            .get_default_config(adapter, size.0.max(1), size.1.max(1))
            .ok_or_else(|| format!("{} cannot present to the window", gpu.info.name))?;
        config.format = format;
        config.view_formats.clear();
        config.present_mode = wgpu::PresentMode::AutoVsync;
        config.alpha_mode = caps.alpha_modes[0];
        surface.configure(&gpu.device, &config);

        let device = gpu.device;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("present"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("present"),
            entries: &[
                entry(0, wgpu::BufferBindingType::Storage { read_only: true }),
                entry(1, wgpu::BufferBindingType::Uniform),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("present"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("present"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("present size"),
            size: 16,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Ok(GpuPresenter { surface, device, queue: gpu.queue, config, pipeline, layout, uniform, picture: None })
    }

    /// Shows the top-left `width` x `height` of `buffer` (`Vec4` elements,
    /// rows of `stride`) as the last launch left it on the device.
    pub fn present(
        &mut self,
        ctx: &Context,
        buffer: BufferId,
        stride: u32,
        (width, height): (u32, u32),
    ) -> Result<(), String> {
        let at = ctx.wgpu_buffer(buffer).map_err(|e| e.to_string())?;
        let picture = self.picture_buffer(at.size, (stride, width, height));
        let mut encoder =
            self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("present") });
        encoder.copy_buffer_to_buffer(&at.buffer, at.offset, &picture, 0, at.size);
        self.queue.submit([encoder.finish()]);
        self.redraw((width, height))
    }

    /// Shows a picture on the host (the viewer's denoised one, read back
    /// and gamma corrected there), written to the device first.
    pub fn present_image(&mut self, image: &crate::Image) -> Result<(), String> {
        let bytes: Vec<u8> = image.pixels.iter().flat_map(|p| p.to_array()).flat_map(|x| x.to_le_bytes()).collect();
        let picture = self.picture_buffer(bytes.len() as u64, (image.width, image.width, image.height));
        self.queue.write_buffer(&picture, 0, &bytes);
        self.redraw((image.width, image.height))
    }

    /// The picture's buffer, holding at least `size` bytes (made anew when
    /// smaller), with the draw told `(stride, width, height)`.
    fn picture_buffer(&mut self, size: u64, (stride, width, height): (u32, u32, u32)) -> wgpu::Buffer {
        if self.picture.as_ref().is_none_or(|(b, _)| b.size() < size) {
            let picture = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("present picture"),
                size: size.max(16),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("present"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: picture.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: self.uniform.as_entire_binding() },
                ],
            });
            self.picture = Some((picture, bind_group));
        }
        let words = [stride, width, height, 0];
        let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
        self.queue.write_buffer(&self.uniform, 0, &bytes);
        self.picture.as_ref().expect("made above").0.clone()
    }

    /// Shows the last picture again (the window was uncovered) at the
    /// window's `size`.
    pub fn redraw(&mut self, (width, height): (u32, u32)) -> Result<(), String> {
        let Some((_, bind_group)) = &self.picture else { return Ok(()) };
        if (self.config.width, self.config.height) != (width, height) {
            self.config.width = width.max(1);
            self.config.height = height.max(1);
            self.surface.configure(&self.device, &self.config);
        }
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => frame,
            // Nothing to draw on now; the next frame tries again.
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => return Ok(()),
            wgpu::CurrentSurfaceTexture::Outdated => {
                self.surface.configure(&self.device, &self.config);
                return Ok(());
            }
            other => return Err(format!("the window's surface failed: {other:?}")),
        };
        let view = frame.texture.create_view(&wgpu::TextureViewDescriptor::default());
        let mut encoder =
            self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("present") });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("present"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
        self.queue.submit([encoder.finish()]);
        self.queue.present(frame);
        Ok(())
    }
}
