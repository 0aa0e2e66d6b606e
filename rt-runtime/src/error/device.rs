//! The device: what the wgpu device or its driver reports, the limits of
//! the adapter a launch does not fit, a lost device, and a wait a browser
//! page cannot make.

/// The device reported a failure, or the launch does not fit it.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DeviceError {
    /// What the device or its driver reported (a validation error, a
    /// shader the device does not compile, an adapter or device that does
    /// not open), in its words.
    #[error("the wgpu backend: {0}")]
    Gpu(String),
    /// A part of the launch (the heap, a scene section) larger than the
    /// device's largest storage binding.
    #[error("the wgpu backend: {what} needs {} but {adapter} binds at most {} per storage buffer", size(*.bytes), size(*.limit))]
    BindingLimit {
        /// What the binding holds (`the heap (variables, buffers, textures)`).
        what: String,
        /// Its size in bytes.
        bytes: u64,
        /// The adapter's name and backend.
        adapter: String,
        /// The most one storage binding holds, in bytes.
        limit: u64,
    },
    /// The wgpu device was lost during a launch.
    #[error(
        "the wgpu device on {adapter} was lost during the launch ({reason}); the launch wrote none of its outputs and the context's data is unchanged: the next launch opens a new device and uploads the scene again"
    )]
    DeviceLost {
        /// The adapter's name.
        adapter: String,
        /// The reason wgpu gave.
        reason: String,
    },
    /// A blocking call where the caller cannot block (a browser page).
    #[error(
        "this call waits for the GPU, which a browser page cannot do in a blocking call: use Context::launch_async"
    )]
    WouldBlock,
    /// A node larger than the adapter's ray-query acceleration structures hold.
    #[error(
        "node {node}: {count} {what} is more than {adapter} builds (at most {limit}); use the compute traversal (`Traversal::Compute`, RT_TRAVERSAL=compute) or split the scene"
    )]
    AccelerationLimit {
        /// The node, by index.
        node: u32,
        /// What is counted (`TLAS instances (paths down to geometry groups)`).
        what: &'static str,
        /// How many the node has.
        count: u64,
        /// The most the adapter builds.
        limit: u64,
        /// The adapter's name.
        adapter: String,
    },
}

/// A size for messages: MiB (one decimal unless whole) from 1 MiB up,
/// KiB below.
pub(crate) fn size(bytes: u64) -> String {
    const MIB: u64 = 1 << 20;
    match bytes {
        b if b >= MIB && b % MIB == 0 => format!("{} MiB", b / MIB),
        b if b >= MIB => format!("{:.1} MiB", b as f64 / MIB as f64),
        b => format!("{} KiB", b.div_ceil(1 << 10)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_binding_limit_names_the_part_the_adapter_and_both_sizes() {
        let e = DeviceError::BindingLimit {
            what: "the scene's BVH nodes".into(),
            bytes: 1_258_292,
            adapter: "llvmpipe (Vulkan)".into(),
            limit: 1 << 20,
        };
        assert_eq!(
            e.to_string(),
            "the wgpu backend: the scene's BVH nodes needs 1.2 MiB but llvmpipe (Vulkan) binds at most 1 MiB per storage buffer"
        );
        assert_eq!(size(1536), "2 KiB");
    }
}
