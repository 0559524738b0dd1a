//! Headless wgpu device creation: Vulkan first (lavapipe on CPU-only
//! machines), then GL. When no adapter exists the error says how to get one.
//!
//! Two requests (`device_needs.rs` maps the manifest's terms to wgpu's):
//! - [`Gpu::for_style`]: exactly what one style needs: WebGPU's default
//!   limits, raised to the manifest's `device_needs`, and its features;
//!   an adapter without one is E0510 naming the pass. `npr render` uses it.
//! - [`Gpu::headless`]: for a host that runs whichever style comes (the
//!   studio, `npr watch`, the benchmarks, the tests): every limit a style
//!   may need at what the adapter allows, and timestamp queries when the
//!   adapter has them. A style it cannot run is E0510 from `Renderer::new`.
//!
//! Both also take the adapter's largest 2D texture: the image size is the
//! host's choice (`--size`, up to `MAX_OUTPUT_SIZE`), not the style's.

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
    /// The adapter lacks a feature or limit the style needs (E0510 each).
    #[error("{}", .0.iter().map(|d| d.message.clone()).collect::<Vec<_>>().join("; "))]
    LacksNeeds(Vec<npr_diag::Diagnostic>),
}

impl DeviceError {
    /// As diagnostics: E0510 per need the adapter lacks; otherwise one
    /// with its code (E0505), the install hint as its help.
    pub fn diagnostics(&self) -> Vec<npr_diag::Diagnostic> {
        match self {
            DeviceError::LacksNeeds(d) => d.clone(),
            _ => vec![self.to_diagnostic()],
        }
    }

    /// As one diagnostic: [`DeviceError::diagnostics`]' first.
    pub fn to_diagnostic(&self) -> npr_diag::Diagnostic {
        match self {
            DeviceError::LacksNeeds(d) => d
                .first()
                .cloned()
                .unwrap_or_else(|| npr_diag::Diagnostic::error(npr_diag::codes::DEVICE_LACKS_NEED, self.to_string())),
            DeviceError::NoAdapter => npr_diag::Diagnostic::error(
                npr_diag::codes::NO_DEVICE,
                "no GPU adapter found (tried Vulkan, then GL)",
            )
            .with_help(
                "on Debian/Ubuntu install the software Vulkan driver: `sudo apt-get install -y \
                 mesa-vulkan-drivers` (or run ./setup.sh), then check with `vulkaninfo --summary`",
            ),
            DeviceError::RequestDevice { .. } => {
                npr_diag::Diagnostic::error(npr_diag::codes::NO_DEVICE, self.to_string())
            }
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
    /// A headless device for whichever style comes, preferring Vulkan,
    /// then GL: every limit a style may need at what the adapter allows,
    /// and timestamp queries (benchmarks) when the adapter has them.
    pub fn headless() -> Result<Gpu, DeviceError> {
        Self::create(|adapter| {
            let limits = crate::device_needs::every_limit_the_adapter_allows(base_limits(adapter), &adapter.limits());
            Ok((adapter.features() & wgpu::Features::TIMESTAMP_QUERY, limits))
        })
    }

    /// A headless device with exactly what `manifest` needs beyond WebGPU's
    /// defaults (its `device_needs`), preferring Vulkan, then GL. An
    /// adapter without a need is E0510, naming it and its pass.
    pub fn for_style(manifest: &npr_abi::Manifest) -> Result<Gpu, DeviceError> {
        Self::create(|adapter| {
            let info = adapter.get_info();
            let lacking = crate::device_needs::unmet(
                manifest,
                adapter.features(),
                &adapter.limits(),
                &format!("the adapter `{}` ({:?})", info.name, info.backend),
            );
            if !lacking.is_empty() {
                return Err(DeviceError::LacksNeeds(lacking));
            }
            let features = manifest
                .required_features()
                .into_iter()
                .fold(wgpu::Features::empty(), |f, need| {
                    f | crate::device_needs::wgpu_feature(need)
                });
            Ok((
                features,
                crate::device_needs::requested_limits(manifest, base_limits(adapter)),
            ))
        })
    }

    /// The first adapter (Vulkan, then GL) with the device `request` asks
    /// of it (features and limits; `Err` refuses the adapter outright).
    fn create(
        request: impl Fn(&wgpu::Adapter) -> Result<(wgpu::Features, wgpu::Limits), DeviceError>,
    ) -> Result<Gpu, DeviceError> {
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
            let (features, limits) = request(&adapter)?;
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

/// WebGPU's default limits, which every conforming device gives, with the
/// adapter's largest 2D texture (the host's image size); on an adapter
/// below WebGPU's defaults (a GL ES one), the downlevel defaults at its
/// resolution, as before there were device needs.
fn base_limits(adapter: &wgpu::Adapter) -> wgpu::Limits {
    let allowed = adapter.limits();
    let mut limits = if wgpu::Limits::default().check_limits(&allowed) {
        wgpu::Limits::default()
    } else {
        wgpu::Limits::downlevel_defaults().using_resolution(allowed.clone())
    };
    limits.max_texture_dimension_2d = limits.max_texture_dimension_2d.max(allowed.max_texture_dimension_2d);
    limits
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
