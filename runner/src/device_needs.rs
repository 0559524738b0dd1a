//! A style's device needs (`Manifest::device_needs`: WebGPU features and
//! limits above the defaults, each with its pass) in wgpu's terms: the
//! features and limits to request ([`requested_limits`]), and the check
//! that refuses a device or adapter without one (E0510) before any
//! pipeline is built, naming the need and the pass that has it.

use npr_abi::manifest::{DeviceNeed, Feature, Limit, Manifest};

/// wgpu's flag for a WebGPU feature.
pub fn wgpu_feature(feature: Feature) -> wgpu::Features {
    match feature {
        Feature::Float32Filterable => wgpu::Features::FLOAT32_FILTERABLE,
        Feature::Float32Blendable => wgpu::Features::FLOAT32_BLENDABLE,
    }
}

/// `limit_value` and `raise`, from one table of WebGPU's limits and
/// wgpu's fields (`max_uniform_buffer_binding_size` is a u64, the rest u32).
macro_rules! limit_fields {
    ($($variant:ident => $field:ident),* $(,)?) => {
        /// The value of WebGPU's `limit` in `limits`.
        pub fn limit_value(limits: &wgpu::Limits, limit: Limit) -> u64 {
            match limit {
                $(Limit::$variant => u64::from(limits.$field),)*
            }
        }

        /// `limit` in `limits` raised to at least `value` (saturating).
        fn raise(limits: &mut wgpu::Limits, limit: Limit, value: u64) {
            match limit {
                $(Limit::$variant => limits.$field = limits.$field.max(value.try_into().unwrap_or(!0)),)*
            }
        }
    };
}

limit_fields! {
    MaxBindGroups => max_bind_groups,
    MaxBindingsPerBindGroup => max_bindings_per_bind_group,
    MaxDynamicUniformBuffersPerPipelineLayout => max_dynamic_uniform_buffers_per_pipeline_layout,
    MaxSampledTexturesPerShaderStage => max_sampled_textures_per_shader_stage,
    MaxSamplersPerShaderStage => max_samplers_per_shader_stage,
    MaxStorageBuffersPerShaderStage => max_storage_buffers_per_shader_stage,
    MaxStorageTexturesPerShaderStage => max_storage_textures_per_shader_stage,
    MaxUniformBuffersPerShaderStage => max_uniform_buffers_per_shader_stage,
    MaxUniformBufferBindingSize => max_uniform_buffer_binding_size,
    MaxVertexBuffers => max_vertex_buffers,
    MaxVertexAttributes => max_vertex_attributes,
    MaxInterStageShaderVariables => max_inter_stage_shader_variables,
    MaxColorAttachments => max_color_attachments,
    MaxColorAttachmentBytesPerSample => max_color_attachment_bytes_per_sample,
    MaxComputeWorkgroupStorageSize => max_compute_workgroup_storage_size,
    MaxComputeInvocationsPerWorkgroup => max_compute_invocations_per_workgroup,
    MaxComputeWorkgroupSizeX => max_compute_workgroup_size_x,
    MaxComputeWorkgroupSizeY => max_compute_workgroup_size_y,
    MaxComputeWorkgroupSizeZ => max_compute_workgroup_size_z,
}

/// `base` with every limit `manifest` needs raised to its value (never
/// lowered: a base above the need stays).
pub fn requested_limits(manifest: &Manifest, base: wgpu::Limits) -> wgpu::Limits {
    let mut limits = base;
    for (limit, value) in manifest.required_limits() {
        raise(&mut limits, limit, value);
    }
    limits
}

/// Every limit npr's styles may need raised to what `adapter` allows: the
/// device of a host that runs whichever style comes (`Gpu::headless`).
pub fn every_limit_the_adapter_allows(base: wgpu::Limits, adapter: &wgpu::Limits) -> wgpu::Limits {
    let mut limits = base;
    for (limit, _, _) in Limit::ALL {
        raise(&mut limits, limit, limit_value(adapter, limit));
    }
    limits
}

/// E0510 for each need of `manifest` that `features` and `limits` (a
/// device's, or an adapter's) do not meet; `what` names them ("this
/// device", "the adapter `llvmpipe`").
pub fn unmet(
    manifest: &Manifest,
    features: wgpu::Features,
    limits: &wgpu::Limits,
    what: &str,
) -> Vec<npr_diag::Diagnostic> {
    manifest
        .every_device_need()
        .into_iter()
        .filter_map(|(filter, need)| {
            let why = match need {
                DeviceNeed::Feature { feature, .. } => {
                    (!features.contains(wgpu_feature(*feature))).then(|| "lacks it".to_string())
                }
                DeviceNeed::Limit { limit, value, .. } => {
                    let allowed = limit_value(limits, *limit);
                    (allowed < *value).then(|| format!("allows {allowed}"))
                }
            }?;
            Some(
                npr_diag::Diagnostic::error(
                    npr_diag::codes::DEVICE_LACKS_NEED,
                    format!(
                        "pass `{}`{} needs {}; {what} {why}",
                        need.pass(),
                        filter
                            .map(|f| format!(" of the art-map filter `{f}`"))
                            .unwrap_or_default(),
                        need.describe()
                    ),
                )
                .with_help(help(need)),
            )
        })
        .collect()
}

/// What to do about a need the device does not meet.
fn help(need: &DeviceNeed) -> String {
    let ask = "a host that creates its own device must request the manifest's `device_needs` \
               (`npr_runner::Gpu::for_style` does)";
    match need {
        DeviceNeed::Feature { .. } => format!("run it on an adapter with the feature; {ask}"),
        DeviceNeed::Limit { limit, .. } => format!(
            "change pass `{}` to need less (fewer outputs, bindings or vertex attributes), or run it \
             on an adapter that allows more `{}`; {ask}",
            need.pass(),
            limit.webgpu_name()
        ),
    }
}
