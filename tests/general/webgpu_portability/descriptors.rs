//! A compiled style as the page side (`tests/data/webgpu_check.js`) takes
//! it: per pass its WGSL and its pipelines as WebGPU descriptors, built
//! from the manifest alone (`npr_abi::manifest::layout`: the bind group
//! layouts, vertex buffers and colour targets it implies; the depth and
//! blend states of `DepthMode` and `Blend`), and the device the style asks
//! for (`Manifest::required_features`, `required_limits`). This is what a
//! host that is not the runner would write, so a browser building these
//! pipelines checks the manifest/WGSL contract with an implementation
//! that is not wgpu.

use npr_abi::manifest::layout::{self, BindingType, LayoutEntry, Visibility};
use npr_abi::manifest::*;
use npr_abi::StyleProgram;
use serde_json::{json, Value};

/// One style for `nprCheck`: `label` names it in failures.
pub fn style(label: &str, program: &StyleProgram) -> Value {
    let features: Vec<&str> = program
        .manifest
        .required_features()
        .into_iter()
        .map(Feature::webgpu_name)
        .collect();
    let limits: serde_json::Map<String, Value> = program
        .manifest
        .required_limits()
        .into_iter()
        .map(|(l, v)| (l.webgpu_name().to_string(), json!(v)))
        .collect();
    let passes: Vec<Value> = program
        .manifest
        .passes
        .iter()
        .map(|pass| {
            json!({
                "name": pass.name,
                "shader": pass.shader,
                "code": program.shaders.get(&pass.shader).cloned().unwrap_or_default(),
                "pipelines": pipelines(&program.manifest, pass),
            })
        })
        .collect();
    json!({"label": label, "features": features, "limits": limits, "passes": passes})
}

/// The art-map filters `program` runs on its textures, each as a program
/// of its own (its passes run on the same device).
pub fn filters(program: &StyleProgram) -> Vec<(String, StyleProgram)> {
    program
        .manifest
        .textures
        .iter()
        .filter_map(|t| match &t.source {
            TextureSourceManifest::Artmap(spec) => Some((spec.filter.path.clone(), spec.filter.program())),
            _ => None,
        })
        .collect()
}

/// The pipelines of `pass`: one render pipeline for the raster kinds, one
/// compute pipeline per entry point for the others.
fn pipelines(manifest: &Manifest, pass: &PassManifest) -> Vec<Value> {
    let groups: Vec<Vec<Value>> = layout::bind_group_layouts(manifest, pass)
        .iter()
        .map(|g| g.iter().map(layout_entry).collect())
        .collect();
    // The runner sets the measured rounding; any value builds the pipeline.
    let constants = if pass.device_half_rounding {
        json!({ npr_abi::formats::HALF_ROUNDING_OVERRIDE: 0 })
    } else {
        json!({})
    };
    if let Some((vertex, fragment)) = pass.kind.raster_entries() {
        return vec![json!({
            "label": format!("{vertex} + {fragment}"),
            "groups": groups,
            "constants": constants,
            "vertex": vertex,
            "fragment": fragment,
            "buffers": layout::vertex_buffers(pass).iter().map(vertex_buffer).collect::<Vec<_>>(),
            "targets": color_targets(manifest, pass),
            "depthStencil": depth_stencil(&pass.kind),
        })];
    }
    pass.kind
        .entries()
        .into_iter()
        .map(|(_, entry)| json!({"label": entry, "groups": groups, "constants": constants, "compute": entry}))
        .collect()
}

/// `GPUBindGroupLayoutEntry`.
fn layout_entry(e: &LayoutEntry) -> Value {
    // GPUShaderStage: VERTEX 1, FRAGMENT 2, COMPUTE 4.
    let visibility = match e.visibility {
        Visibility::VertexFragment => 3,
        Visibility::Vertex => 1,
        Visibility::Compute => 4,
    };
    let mut v = json!({"binding": e.binding, "visibility": visibility});
    match e.ty {
        BindingType::UniformBuffer {
            dynamic_offset,
            min_binding_size,
        } => {
            v["buffer"] =
                json!({"type": "uniform", "hasDynamicOffset": dynamic_offset, "minBindingSize": min_binding_size})
        }
        BindingType::StorageBuffer { read_only } => {
            v["buffer"] = json!({"type": if read_only { "read-only-storage" } else { "storage" }})
        }
        BindingType::Texture { filterable } => {
            v["texture"] =
                json!({"sampleType": if filterable { "float" } else { "unfilterable-float" }, "viewDimension": "2d"})
        }
        BindingType::DepthTexture => v["texture"] = json!({"sampleType": "depth", "viewDimension": "2d"}),
        BindingType::FilteringSampler => v["sampler"] = json!({"type": "filtering"}),
        BindingType::WriteOnlyStorageTexture { format } => {
            v["storageTexture"] = json!({"access": "write-only", "format": format, "viewDimension": "2d"})
        }
    }
    v
}

/// `GPUVertexBufferLayout`.
fn vertex_buffer(b: &layout::VertexBufferLayout) -> Value {
    let attributes: Vec<Value> = b
        .attributes
        .iter()
        .map(|a| {
            let format = match a.components {
                1 => "float32".to_string(),
                n => format!("float32x{n}"),
            };
            json!({"format": format, "offset": a.offset, "shaderLocation": a.location})
        })
        .collect();
    json!({"arrayStride": b.array_stride, "stepMode": "vertex", "attributes": attributes})
}

/// `GPUColorTargetState` per output, with the blend of its mode.
fn color_targets(manifest: &Manifest, pass: &PassManifest) -> Vec<Value> {
    let component = |src: &str, dst: &str| json!({"srcFactor": src, "dstFactor": dst, "operation": "add"});
    pass.outputs
        .iter()
        .enumerate()
        .map(|(k, t)| {
            // `Format` serializes as WebGPU spells it (`rgba8unorm-srgb`).
            let mut target = json!({"format": manifest.targets[*t].format});
            let both = |c: Value| json!({"color": c, "alpha": c});
            match pass.blend.get(k).copied().unwrap_or_default() {
                Blend::Replace => {}
                Blend::Over => {
                    target["blend"] = json!({
                        "color": component("src-alpha", "one-minus-src-alpha"),
                        "alpha": component("one", "one-minus-src-alpha"),
                    })
                }
                Blend::Add => target["blend"] = both(component("one", "one")),
                Blend::Multiply => target["blend"] = both(component("dst", "zero")),
            }
            target
        })
        .collect()
}

/// `GPUDepthStencilState` of a render pass's depth mode; none for the
/// other kinds (a lines pass tests depth in its shader).
fn depth_stencil(kind: &PassKindManifest) -> Value {
    let PassKindManifest::Render { depth, .. } = kind else {
        return Value::Null;
    };
    let (write, compare, slope) = match depth {
        DepthMode::Own | DepthMode::Keep => (true, "less", 0.0),
        DepthMode::Test { bias_px, .. } | DepthMode::TestInput { bias_px, .. } => (false, "less-equal", -bias_px),
    };
    json!({"format": "depth32float", "depthWriteEnabled": write, "depthCompare": compare, "depthBiasSlopeScale": slope})
}
