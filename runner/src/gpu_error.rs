//! wgpu errors caught on purpose, never left to wgpu's default handler
//! (which panics).
//!
//! Every piece of GPU work the runner starts (building a [`crate::Renderer`],
//! sizing its textures, a frame's submission, a read-back) runs in
//! `scoped`, inside out-of-memory, validation and internal error scopes:
//! - out of memory is [`RunError::OutOfMemory`] (E0508, exit 1) with a hint;
//! - a validation or internal error is [`RunError::Internal`] (E9001): the
//!   compiler's WGSL is validated by naga and its manifest by
//!   `npr_abi::validate`, so wgpu refusing them is a bug in npr;
//! - a lost device (a driver reset, `Device::destroy`) is not reported
//!   through scopes at all (wgpu drops those errors and signals the loss to
//!   the device-lost callback), so [`DeviceWatch`], which `Gpu::headless`
//!   installs, records it, and [`DeviceWatch::check`] turns whatever error
//!   the loss caused into [`RunError::DeviceLost`] (E0509).
//!
//! A format the adapter cannot render to is checked before any pipeline is
//! built ([`check_target_formats`]): a user-facing limit (E0404) with an
//! install hint, not a validation error.

use crate::gpu_count::Create;
use crate::RunError;
use npr_abi::Format;
use std::sync::{Arc, Mutex};

/// Run `work` inside out-of-memory, validation and internal error scopes;
/// a wgpu error it caused wins over its own result. `what` names the work
/// for the message ("building the renderer", "a 4096x4096 frame").
pub(crate) fn scoped<T>(
    device: &wgpu::Device,
    what: impl Fn() -> String,
    work: impl FnOnce() -> Result<T, RunError>,
) -> Result<T, RunError> {
    let oom = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let internal = device.push_error_scope(wgpu::ErrorFilter::Internal);
    let result = work();
    // Scopes pop in reverse order of their pushes.
    let internal = pollster::block_on(internal.pop());
    let validation = pollster::block_on(validation.pop());
    let oom = pollster::block_on(oom.pop());
    match oom.or(validation).or(internal) {
        Some(e) => Err(classify(&e, &what())),
        None => result,
    }
}

/// A wgpu error as npr reports it.
fn classify(e: &wgpu::Error, what: &str) -> RunError {
    match e {
        wgpu::Error::OutOfMemory { .. } => RunError::OutOfMemory(format!("the GPU ran out of memory {what}")),
        wgpu::Error::Validation { description, .. } => {
            RunError::Internal(format!("wgpu refused {what}: {description}"))
        }
        wgpu::Error::Internal { description, .. } => RunError::Internal(format!("wgpu failed {what}: {description}")),
    }
}

/// What a device npr owns has reported outside error scopes: its loss, and
/// the first error no scope caught (instead of wgpu's panicking default).
#[derive(Clone, Default)]
pub struct DeviceWatch {
    lost: Arc<Mutex<Option<String>>>,
    uncaptured: Arc<Mutex<Option<String>>>,
}

impl DeviceWatch {
    /// Install the device-lost callback and the uncaptured-error handler.
    pub fn install(device: &wgpu::Device) -> DeviceWatch {
        let watch = DeviceWatch::default();
        let lost = watch.lost.clone();
        device.set_device_lost_callback(move |reason, message| {
            if let Ok(mut slot) = lost.lock() {
                slot.get_or_insert(format!("{reason:?}: {message}"));
            }
        });
        let uncaptured = watch.uncaptured.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            if let Ok(mut slot) = uncaptured.lock() {
                slot.get_or_insert(e.to_string());
            }
        }));
        watch
    }

    /// Why the device was lost, if it was.
    pub fn lost(&self) -> Option<String> {
        self.lost.lock().ok().and_then(|s| s.clone())
    }

    /// `result`, unless the device was lost (then [`RunError::DeviceLost`],
    /// whatever the work returned: after a loss every operation fails) or
    /// an error escaped every scope (then an internal error with it).
    pub fn check<T>(&self, result: Result<T, RunError>) -> Result<T, RunError> {
        if let Some(reason) = self.lost() {
            return Err(RunError::DeviceLost(reason));
        }
        if let Some(e) = self.uncaptured.lock().ok().and_then(|mut s| s.take()) {
            return Err(RunError::Internal(format!(
                "wgpu reported an error outside npr's checks: {e}"
            )));
        }
        result
    }
}

/// The usages a target's texture is created with (`exec::resources`).
pub(crate) const TARGET_USAGE: wgpu::TextureUsages = wgpu::TextureUsages::RENDER_ATTACHMENT
    .union(wgpu::TextureUsages::TEXTURE_BINDING)
    .union(wgpu::TextureUsages::COPY_SRC);

/// E0404 for each of `formats` (with the target that has it) that the
/// device cannot create with `usage`: wgpu checks a texture's usages
/// against the adapter's format features at creation, so a 1×1 texture per
/// format says what a pipeline build would fail on, with no adapter handle.
pub fn check_target_formats(
    device: &wgpu::Device,
    targets: &[(String, Format)],
    usage: wgpu::TextureUsages,
) -> Vec<npr_diag::Diagnostic> {
    let mut checked: Vec<Format> = Vec::new();
    let mut out = Vec::new();
    for (name, format) in targets {
        if checked.contains(format) {
            continue;
        }
        checked.push(*format);
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let _probe = device.make_texture(&wgpu::TextureDescriptor {
            label: Some("npr format probe"),
            size: wgpu::Extent3d {
                width: 1,
                height: 1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: crate::wgpu_format(*format),
            usage,
            view_formats: &[],
        });
        if let Some(e) = pollster::block_on(scope.pop()) {
            out.push(
                npr_diag::Diagnostic::error(
                    npr_diag::codes::LIMIT_EXCEEDED,
                    format!(
                        "this GPU adapter cannot render to `{}` targets (target `{name}`)",
                        format.name()
                    ),
                )
                .with_note(format!("wgpu: {e}"))
                .with_help(
                    "use a Vulkan adapter, which has every format npr writes (on Debian/Ubuntu: `sudo apt-get \
                     install -y mesa-vulkan-drivers`, or ./setup.sh), or give the target another format \
                     (`rgba16float` is renderable everywhere)",
                ),
            );
        }
    }
    out
}
