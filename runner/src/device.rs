//! Headless wgpu device creation: Vulkan first (lavapipe on CPU-only
//! machines), then GL. When no adapter exists the error says how to get one.

use thiserror::Error;

#[derive(Debug, Error)]
pub enum DeviceError {
    #[error(
        "no GPU adapter found (tried Vulkan, then GL).\n\
         help: on Debian/Ubuntu install the software Vulkan driver: \
         `sudo apt-get install -y mesa-vulkan-drivers` (or run ./setup.sh), \
         then check with `vulkaninfo --summary`"
    )]
    NoAdapter,
    #[error("the GPU adapter `{adapter}` refused to create a device: {source}")]
    RequestDevice {
        adapter: String,
        #[source]
        source: wgpu::RequestDeviceError,
    },
}

impl DeviceError {
    /// As a diagnostic with its code (E0505), the install hint as its help.
    pub fn to_diagnostic(&self) -> diag::Diagnostic {
        match self {
            DeviceError::NoAdapter => {
                diag::Diagnostic::error(diag::codes::NO_DEVICE, "no GPU adapter found (tried Vulkan, then GL)")
                    .with_help(
                        "on Debian/Ubuntu install the software Vulkan driver: `sudo apt-get install -y \
                 mesa-vulkan-drivers` (or run ./setup.sh), then check with `vulkaninfo --summary`",
                    )
            }
            DeviceError::RequestDevice { .. } => diag::Diagnostic::error(diag::codes::NO_DEVICE, self.to_string()),
        }
    }
}

/// A device and queue owned by npr (the headless case). Library users who
/// bring their own device pass `&wgpu::Device` and `&wgpu::Queue` directly.
pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter_info: wgpu::AdapterInfo,
    /// The device's loss and any error no scope caught (`gpu_error`).
    pub watch: crate::DeviceWatch,
}

impl Gpu {
    /// Create a headless device, preferring Vulkan, then GL.
    pub fn headless() -> Result<Gpu, DeviceError> {
        silence_loader_warning();
        for backends in [wgpu::Backends::VULKAN, wgpu::Backends::GL] {
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
            desc.backends = backends;
            // Creating a texture or buffer past 90% of the memory budget the
            // driver reports is an out-of-memory error (E0508), not an
            // allocation the OS may kill the process for (where the backend
            // reports a budget: Vulkan with VK_EXT_memory_budget, D3D12).
            desc.memory_budget_thresholds = wgpu::MemoryBudgetThresholds {
                for_resource_creation: Some(90),
                for_device_loss: None,
            };
            let instance = wgpu::Instance::new(desc);
            let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter: false,
                compatible_surface: None,
                ..Default::default()
            }));
            let Ok(adapter) = adapter else { continue };
            let info = adapter.get_info();
            let mut limits = wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits());
            limits.max_color_attachments = limits
                .max_color_attachments
                .max(8)
                .min(adapter.limits().max_color_attachments);
            limits.max_color_attachment_bytes_per_sample = adapter.limits().max_color_attachment_bytes_per_sample;
            limits.max_texture_dimension_2d = adapter.limits().max_texture_dimension_2d;
            // Compute passes bind their objects, members, vertex attributes,
            // values and partials as storage buffers (downlevel allows 4).
            limits.max_storage_buffers_per_shader_stage = adapter.limits().max_storage_buffers_per_shader_stage;
            let features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
            let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
                label: Some("npr"),
                required_features: features,
                required_limits: limits,
                ..Default::default()
            }))
            .map_err(|source| DeviceError::RequestDevice {
                adapter: info.name.clone(),
                source,
            })?;
            let watch = crate::DeviceWatch::install(&device);
            return Ok(Gpu {
                watch,
                device,
                queue,
                adapter_info: info,
            });
        }
        Err(DeviceError::NoAdapter)
    }

    pub fn describe(&self) -> String {
        format!("{} ({:?})", self.adapter_info.name, self.adapter_info.backend)
    }
}

/// The Vulkan loader prints "XDG_RUNTIME_DIR is invalid" when the variable is
/// unset; it is harmless, so point it at a private temp dir.
fn silence_loader_warning() {
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        let dir = std::env::temp_dir().join("npr-xdg-runtime");
        if std::fs::create_dir_all(&dir).is_ok() {
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                let _ = std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700));
            }
            // SAFETY: called before any thread of ours reads the environment
            // (device creation is the first thing npr does).
            unsafe { std::env::set_var("XDG_RUNTIME_DIR", &dir) };
        }
    }
}
