//! The GPU side: a minimal wgpu harness (not the runtime's) that runs one
//! compute shader over a heap of words and reads the heap back, and the
//! assembly of a batch of lowered programs into one such shader.
//!
//! A batch module is the compiler's output for each program minus its stub
//! prelude (types, functions, program), behind a prelude of our own that
//! defines the runtime items the programs can name (`PRELUDE`: the
//! compiler's stub prelude with `rt_launch_index` and `rt_launch_dim`
//! answering for the lane being run). The entry point `fz_main` runs one
//! workgroup of [`LANES`] lanes per program: workgroup `y` selects the
//! program in a `switch`, each lane loads the program's `#[var]` inputs
//! from the heap with the compiler's own loaders and calls it with
//! `RtBuffer`s over its slices of the heap. One module and one pipeline
//! per batch amortise lavapipe's shader compile over many programs.

use rt_compiler::types::Ty;

/// Launch indices per program (`launch_index().x` is `0..LANES`).
pub const LANES: u32 = 64;

/// A wgpu device for the fuzzer. A program can make the driver lose the
/// device (lavapipe fails to compile some shaders); the device is then
/// opened again for the next run.
pub struct Gpu {
    inner: std::cell::RefCell<Device>,
    /// The adapter, in words.
    pub name: String,
}

struct Device {
    device: wgpu::Device,
    queue: wgpu::Queue,
    lost: std::sync::Arc<std::sync::Mutex<Option<String>>>,
}

impl Gpu {
    /// Opens the first adapter wgpu finds (a GPU, else lavapipe), as the
    /// runtime does.
    pub fn new() -> Result<Gpu, String> {
        let (device, name) = Gpu::open()?;
        Ok(Gpu { inner: std::cell::RefCell::new(device), name })
    }

    fn open() -> Result<(Device, String), String> {
        let instance = rt_runtime::backend::wgpu::instance();
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        }))
        .map_err(|e| format!("no wgpu adapter: {e}"))?;
        let info = adapter.get_info();
        let limits = wgpu::Limits { max_storage_buffers_per_shader_stage: 4, ..wgpu::Limits::downlevel_defaults() }
            .using_resolution(adapter.limits());
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("rt-fuzz"),
            required_limits: limits,
            ..Default::default()
        }))
        .map_err(|e| format!("cannot open a device on {}: {e}", info.name))?;
        let lost = std::sync::Arc::new(std::sync::Mutex::new(None));
        let flag = lost.clone();
        device.set_device_lost_callback(move |reason, msg| *flag.lock().unwrap() = Some(format!("{reason:?}: {msg}")));
        let name = format!("{} ({:?}, {:?})", info.name, info.device_type, info.backend);
        Ok((Device { device, queue, lost }, name))
    }

    /// Compiles `wgsl` (entry point `fz_main`, `rt_heap` at group 0 binding
    /// 0), runs `groups` workgroups over `heap` and returns the heap after.
    pub fn run(&self, wgsl: &str, heap: &[u32], groups: (u32, u32, u32)) -> Result<Vec<u32>, String> {
        let r = self.inner.borrow().run(wgsl, heap, groups);
        let lost = self.inner.borrow().lost.lock().unwrap().clone();
        match lost {
            Some(why) => {
                *self.inner.borrow_mut() = Gpu::open()?.0;
                Err(format!("the driver lost the device ({why})"))
            }
            None => r,
        }
    }
}

impl Device {
    fn run(&self, wgsl: &str, heap: &[u32], groups: (u32, u32, u32)) -> Result<Vec<u32>, String> {
        use wgpu::util::DeviceExt;
        let internal = self.device.push_error_scope(wgpu::ErrorFilter::Internal);
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = self.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("rt-fuzz batch"),
            source: wgpu::ShaderSource::Wgsl(wgsl.into()),
        });
        // An explicit layout: a module need not use the heap.
        let layout = self.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rt-fuzz"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only: false },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let pipeline_layout = self.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("rt-fuzz"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = self.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("rt-fuzz batch"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("fz_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let validation = pollster::block_on(scope.pop());
        let internal = pollster::block_on(internal.pop());
        if let Some(e) = validation.or(internal) {
            return Err(format!("the batch module does not compile: {e}"));
        }
        if let Some(why) = self.lost.lock().unwrap().clone() {
            return Err(format!("the driver lost the device compiling the module ({why})"));
        }
        let bytes: Vec<u8> = heap.iter().flat_map(|w| w.to_le_bytes()).collect();
        let buffer = self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("rt_heap"),
            contents: &bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        });
        let readback = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rt-fuzz readback"),
            size: bytes.len() as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rt-fuzz"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() }],
        });
        let mut encoder = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
        {
            let mut pass =
                encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: None, timestamp_writes: None });
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind, &[]);
            pass.dispatch_workgroups(groups.0, groups.1, groups.2);
        }
        encoder.copy_buffer_to_buffer(&buffer, 0, &readback, 0, bytes.len() as u64);
        self.queue.submit([encoder.finish()]);
        let slice = readback.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        self.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| format!("device lost: {e}"))?;
        let words = {
            let data = slice.get_mapped_range().map_err(|e| format!("reading back: {e}"))?;
            data.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
        };
        readback.unmap();
        Ok(words)
    }
}

/// The prelude of a batch module: the compiler's stub prelude, with the
/// launch index and size of the lane being run and the buffer bounds checks
/// (the runtime's, less the exception: an index out of range is dropped).
pub fn prelude() -> String {
    let dim = format!("vec2<u32>({LANES}u, 1u)");
    let bodies = [
        ("rt_launch_index", "return vec2<u32>(fz_lane, 0u);".to_string()),
        ("rt_launch_dim", format!("return {dim};")),
        ("rt_buf_check", "return i < b.len;".to_string()),
        ("rt_buf_check2", "return i.x < b.width && i.y < b.height;".to_string()),
    ];
    let mut s = rt_compiler::lower::PRELUDE.clone();
    for (name, body) in bodies {
        let f = rt_abi::intrinsics::wgsl_functions().find(|f| f.name == name).expect("a function of the contract");
        let stub = rt_abi::wgsl::stub(f);
        assert!(s.contains(&stub), "the stub prelude has no `{stub}`");
        s = s.replace(&stub, &format!("{} {{ {body} }}", rt_abi::wgsl::signature(f)));
    }
    s.insert_str(0, "var<private> fz_lane: u32;\n");
    s
}

/// Where one program of a batch finds its inputs and writes its outputs:
/// its plain-data `#[var]`s, packed in declaration order, at
/// `input_base + lane * input_words`; its buffer `#[var]`s, in declaration
/// order, at `(heap word offset, elements)` each.
pub struct Slot {
    pub input_base: u32,
    pub input_words: u32,
    pub buffers: Vec<(u32, u32)>,
}

/// Concatenates the programs' types, functions (deduplicated by name: the
/// compiler's accessors are shared) and programs behind [`prelude`], with a
/// `fz_main` that runs program `workgroup_id.y` for lane `local_invocation_id.x`.
pub fn assemble(parts: &[&rt_compiler::Lowered], slots: &[Slot]) -> String {
    let mut out = prelude();
    let mut seen: std::collections::HashMap<String, String> = std::collections::HashMap::new();
    for l in parts {
        for (name, text) in l.types.iter().chain(&l.functions) {
            match seen.get(name) {
                Some(prev) => assert_eq!(prev, text, "two programs define `{name}` differently"),
                None => {
                    seen.insert(name.clone(), text.clone());
                    out.push('\n');
                    out.push_str(text);
                }
            }
        }
    }
    for l in parts {
        out.push('\n');
        out.push_str(&l.program);
    }
    out.push_str(&format!(
        "\n@compute @workgroup_size({LANES})\nfn fz_main(@builtin(local_invocation_id) lid: vec3<u32>, @builtin(workgroup_id) wid: vec3<u32>) {{\n    fz_lane = lid.x;\n    switch wid.y {{\n"
    ));
    for (i, s) in slots.iter().enumerate() {
        // The compiler's WGSL takes a ray-generation program's variables
        // in declaration order.
        let mut args = Vec::new();
        let mut offset = 0;
        let mut buffers = s.buffers.iter();
        for (_, t) in &parts[i].variables {
            if let Ty::Buffer(..) = t {
                let (o, n) = buffers.next().expect("a buffer slot per buffer variable");
                args.push(format!("RtBuffer({o}u, {n}u, {n}u, 1u)"));
            } else {
                args.push(format!("rt_load_{}(w + {offset}u)", t.mangle()));
                offset += t.words();
            }
        }
        assert_eq!(offset, s.input_words, "input words of program {i}");
        out.push_str(&format!(
            "        case {i}u: {{\n            let w = {}u + lid.x * {}u;\n            {}({});\n        }}\n",
            s.input_base,
            s.input_words,
            parts[i].wgsl_entry,
            args.join(", ")
        ));
    }
    out.push_str("        default: {}\n    }\n}\n");
    out
}
