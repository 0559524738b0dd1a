//! What a style needs of the WebGPU device beyond what every conforming
//! implementation gives without being asked: optional features, and limits
//! above WebGPU's defaults. Each need names the pass that has it, so a
//! device without it is refused with a message that says which pass to
//! change. The compiler computes them (`npr_compiler::back::device_needs`,
//! from [`super::layout`] and the validated shaders); a host requests
//! exactly [`Manifest::required_features`] and [`Manifest::required_limits`]
//! (`npr_runner::Gpu::for_style`, or `requestDevice` in a browser); the runner
//! refuses a device that lacks one before the first frame (E0510).
//!
//! Names are WebGPU's own (`float32-filterable`,
//! `maxStorageBuffersPerShaderStage`), so a host in another language maps
//! them without a table.

use super::*;
use std::collections::{BTreeMap, BTreeSet};

/// An optional WebGPU feature a style may need.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Feature {
    /// Filtering samplers on 32-bit float textures.
    Float32Filterable,
    /// Blending into 32-bit float colour attachments.
    Float32Blendable,
}

impl Feature {
    pub const ALL: [Feature; 2] = [Feature::Float32Filterable, Feature::Float32Blendable];

    /// WebGPU's name (`GPUFeatureName`).
    pub fn webgpu_name(self) -> &'static str {
        match self {
            Feature::Float32Filterable => "float32-filterable",
            Feature::Float32Blendable => "float32-blendable",
        }
    }
}

/// A WebGPU limit a style may need above its default. Every one is a
/// maximum: a device allowing more than needed is fine.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Limit {
    MaxBindGroups,
    MaxBindingsPerBindGroup,
    MaxDynamicUniformBuffersPerPipelineLayout,
    MaxSampledTexturesPerShaderStage,
    MaxSamplersPerShaderStage,
    MaxStorageBuffersPerShaderStage,
    MaxStorageTexturesPerShaderStage,
    MaxUniformBuffersPerShaderStage,
    MaxUniformBufferBindingSize,
    MaxVertexBuffers,
    MaxVertexAttributes,
    MaxInterStageShaderVariables,
    MaxColorAttachments,
    MaxColorAttachmentBytesPerSample,
    MaxComputeWorkgroupStorageSize,
    MaxComputeInvocationsPerWorkgroup,
    MaxComputeWorkgroupSizeX,
    MaxComputeWorkgroupSizeY,
    MaxComputeWorkgroupSizeZ,
}

impl Limit {
    /// Every limit with its WebGPU name and default (the spec's table of
    /// limits: what every device gives unless asked for more).
    pub const ALL: [(Limit, &'static str, u64); 19] = [
        (Limit::MaxBindGroups, "maxBindGroups", 4),
        (Limit::MaxBindingsPerBindGroup, "maxBindingsPerBindGroup", 1000),
        (
            Limit::MaxDynamicUniformBuffersPerPipelineLayout,
            "maxDynamicUniformBuffersPerPipelineLayout",
            8,
        ),
        (
            Limit::MaxSampledTexturesPerShaderStage,
            "maxSampledTexturesPerShaderStage",
            16,
        ),
        (Limit::MaxSamplersPerShaderStage, "maxSamplersPerShaderStage", 16),
        (
            Limit::MaxStorageBuffersPerShaderStage,
            "maxStorageBuffersPerShaderStage",
            8,
        ),
        (
            Limit::MaxStorageTexturesPerShaderStage,
            "maxStorageTexturesPerShaderStage",
            4,
        ),
        (
            Limit::MaxUniformBuffersPerShaderStage,
            "maxUniformBuffersPerShaderStage",
            12,
        ),
        (Limit::MaxUniformBufferBindingSize, "maxUniformBufferBindingSize", 65536),
        (Limit::MaxVertexBuffers, "maxVertexBuffers", 8),
        (Limit::MaxVertexAttributes, "maxVertexAttributes", 16),
        (Limit::MaxInterStageShaderVariables, "maxInterStageShaderVariables", 16),
        (Limit::MaxColorAttachments, "maxColorAttachments", 8),
        (
            Limit::MaxColorAttachmentBytesPerSample,
            "maxColorAttachmentBytesPerSample",
            32,
        ),
        (
            Limit::MaxComputeWorkgroupStorageSize,
            "maxComputeWorkgroupStorageSize",
            16384,
        ),
        (
            Limit::MaxComputeInvocationsPerWorkgroup,
            "maxComputeInvocationsPerWorkgroup",
            256,
        ),
        (Limit::MaxComputeWorkgroupSizeX, "maxComputeWorkgroupSizeX", 256),
        (Limit::MaxComputeWorkgroupSizeY, "maxComputeWorkgroupSizeY", 256),
        (Limit::MaxComputeWorkgroupSizeZ, "maxComputeWorkgroupSizeZ", 64),
    ];

    fn row(self) -> (Limit, &'static str, u64) {
        Self::ALL
            .into_iter()
            .find(|(l, _, _)| *l == self)
            .unwrap_or((self, "?", 0))
    }

    /// WebGPU's name (a member of `GPUSupportedLimits`).
    pub fn webgpu_name(self) -> &'static str {
        self.row().1
    }

    /// WebGPU's default: what a device has when nobody asks for more.
    pub fn default_value(self) -> u64 {
        self.row().2
    }
}

/// One thing a pass needs of the device beyond WebGPU's defaults.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "need", rename_all = "snake_case")]
pub enum DeviceNeed {
    /// An optional feature.
    Feature { pass: String, feature: Feature },
    /// A limit of at least `value` (above the limit's default).
    Limit { pass: String, limit: Limit, value: u64 },
}

impl DeviceNeed {
    /// The pass that has the need.
    pub fn pass(&self) -> &str {
        match self {
            DeviceNeed::Feature { pass, .. } | DeviceNeed::Limit { pass, .. } => pass,
        }
    }

    /// What is needed, as a message says it: "the feature
    /// `float32-filterable`", "`maxStorageBuffersPerShaderStage` ≥ 10".
    pub fn describe(&self) -> String {
        match self {
            DeviceNeed::Feature { feature, .. } => format!("the WebGPU feature `{}`", feature.webgpu_name()),
            DeviceNeed::Limit { limit, value, .. } => format!(
                "the WebGPU limit `{}` of at least {value} (the default is {})",
                limit.webgpu_name(),
                limit.default_value()
            ),
        }
    }
}

impl Manifest {
    /// Every need of the style, each with the art-map filter it comes from
    /// (`None`: the style's own passes): a filter runs on the style's
    /// textures on the same device, so its needs are the style's too.
    pub fn every_device_need(&self) -> Vec<(Option<&str>, &DeviceNeed)> {
        let mut out: Vec<(Option<&str>, &DeviceNeed)> = self.device_needs.iter().map(|n| (None, n)).collect();
        for t in &self.textures {
            if let TextureSourceManifest::Artmap(spec) = &t.source {
                let path = spec.filter.path.as_str();
                out.extend(
                    spec.filter
                        .manifest
                        .every_device_need()
                        .into_iter()
                        .map(|(_, n)| (Some(path), n)),
                );
            }
        }
        out
    }

    /// Every feature some pass needs (art-map filters' included).
    pub fn required_features(&self) -> BTreeSet<Feature> {
        self.every_device_need()
            .into_iter()
            .filter_map(|(_, n)| match n {
                DeviceNeed::Feature { feature, .. } => Some(*feature),
                DeviceNeed::Limit { .. } => None,
            })
            .collect()
    }

    /// Every limit some pass needs above its default (art-map filters'
    /// included), at the largest value any pass needs.
    pub fn required_limits(&self) -> BTreeMap<Limit, u64> {
        let mut out: BTreeMap<Limit, u64> = BTreeMap::new();
        for (_, n) in self.every_device_need() {
            if let DeviceNeed::Limit { limit, value, .. } = n {
                let v = out.entry(*limit).or_default();
                *v = (*v).max(*value);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_webgpus_in_the_json_too() {
        for (limit, name, default) in Limit::ALL {
            assert_eq!(serde_json::to_value(limit).expect("json"), serde_json::json!(name));
            assert_eq!(limit.webgpu_name(), name);
            assert_eq!(limit.default_value(), default);
        }
        for f in Feature::ALL {
            assert_eq!(
                serde_json::to_value(f).expect("json"),
                serde_json::json!(f.webgpu_name())
            );
        }
        let need = DeviceNeed::Limit {
            pass: "blur".into(),
            limit: Limit::MaxStorageTexturesPerShaderStage,
            value: 5,
        };
        let json = serde_json::to_value(&need).expect("json");
        assert_eq!(
            json,
            serde_json::json!({"need": "limit", "pass": "blur", "limit": "maxStorageTexturesPerShaderStage", "value": 5})
        );
        assert_eq!(serde_json::from_value::<DeviceNeed>(json).expect("back"), need);
    }
}
