//! Binding declarations of one pass and the manifest's `Binding` lists that
//! describe them to the runner. Group 0 (every kind): the frame block, the
//! style-parameter block, targets (this eye's, then the other eye's),
//! style textures and their samplers, the linear clamp sampler, the
//! per-object values of compute passes. Group 1 (kinds that run per
//! object): the `Object` block, then per-object textures.

use super::uses::Uses;
use super::Emitter;
use crate::ir::*;
use npr_abi::manifest::{Binding, ParamBinding, Resource};
use std::collections::BTreeMap;
use std::fmt::Write;

/// The declarations of a pass and what they bind.
pub(super) struct Declared {
    pub text: String,
    pub bindings: Vec<Binding>,
    /// Group 1 after the `Object` block (binding 0): per-object textures.
    pub object_bindings: Vec<Binding>,
    /// WGSL names of the targets read, this eye's and the other eye's.
    /// The binding name of each target read, per copy.
    pub target_names: BTreeMap<(TargetCopy, TargetRef), String>,
}

impl Emitter<'_> {
    /// The WGSL name of a target's binding (a target computed in tiles has
    /// no binding, but its reads keep this name until `emit/tiled`
    /// redirects them).
    pub(super) fn target_binding_name(&self, copy: TargetCopy, t: TargetRef) -> String {
        let prefix = match copy {
            TargetCopy::This => "t_",
            TargetCopy::OtherEye => "t_other_",
            TargetCopy::Previous => "t_prev_",
        };
        format!("{prefix}{}", self.ir.target_name(t).replace('.', "_"))
    }

    pub(super) fn declare(&self, kind: &PassKind, uses: &Uses, uses_frame: bool) -> Declared {
        let mut d = Declared {
            text: String::new(),
            bindings: Vec::new(),
            object_bindings: Vec::new(),
            target_names: BTreeMap::new(),
        };
        let mut next = 0u32;
        if uses_frame {
            d.text.push_str(npr_abi::FRAME_WGSL);
            let _ = writeln!(d.text, "@group(0) @binding({next}) var<uniform> frame: Frame;");
            d.bind(next, Resource::FrameUniforms);
            next += 1;
        }
        if uses.style_params {
            d.text.push_str("struct Params {\n");
            self.param_fields(&mut d.text, ParamBinding::Uniform);
            d.text.push_str("}\n");
            let _ = writeln!(d.text, "@group(0) @binding({next}) var<uniform> params: Params;");
            d.bind(next, Resource::StyleUniforms);
            next += 1;
        }
        // This frame's targets, then (stereo styles) the other eye's copies,
        // then the previous frame's (history targets).
        for (copy, t) in &uses.targets {
            let Some(index) = self.alloc.target_index(*t) else {
                continue;
            };
            let note = match copy {
                TargetCopy::This => "",
                TargetCopy::OtherEye => ", the other eye's",
                TargetCopy::Previous => ", the previous frame's",
            };
            let name = self.target_binding_name(*copy, *t);
            let fmt = self.ir.pass(t.pass).outputs[t.output as usize].format;
            let _ = writeln!(
                d.text,
                "@group(0) @binding({next}) var {name}: texture_2d<f32>; // {}{note}",
                fmt.name()
            );
            d.bind(
                next,
                Resource::Target {
                    target: index,
                    filterable: fmt.is_filterable(),
                    copy: *copy,
                },
            );
            d.target_names.insert((*copy, *t), name);
            next += 1;
        }
        for t in uses
            .textures
            .iter()
            .filter(|t| !self.ir.textures[t.0 as usize].per_object)
        {
            let tex = &self.ir.textures[t.0 as usize];
            let _ = writeln!(
                d.text,
                "@group(0) @binding({next}) var tex_{}: texture_2d<f32>;",
                tex.name
            );
            d.bind(next, Resource::Texture { texture: t.0 as usize });
            next += 1;
            let _ = writeln!(d.text, "@group(0) @binding({next}) var samp_{}: sampler;", tex.name);
            d.bind(next, Resource::TextureSampler { texture: t.0 as usize });
            next += 1;
        }
        if uses.linear_sampler {
            let _ = writeln!(d.text, "@group(0) @binding({next}) var samp_linear_clamp: sampler;");
            d.bind(next, Resource::LinearClampSampler);
            next += 1;
        }
        // Per-object values of earlier compute passes, this frame's.
        for p in &uses.object_values {
            let Some(index) = self.alloc.pass_index(*p) else {
                continue;
            };
            let name = &self.ir.pass(*p).name;
            let _ = writeln!(
                d.text,
                "@group(0) @binding({next}) var<storage, read> v_{name}: array<vec4<f32>>; // per-object values of `{name}`"
            );
            d.bind(next, Resource::ObjectValues { pass: index });
            next += 1;
        }
        if kind.has_object() {
            self.object_group(&mut d, kind, uses);
        }
        d
    }

    /// Group 1: the `Object` block (per-object params), then the per-object
    /// textures, so one bind group per object carries its uniforms and images.
    fn object_group(&self, d: &mut Declared, kind: &PassKind, uses: &Uses) {
        d.text.push_str("struct Object {\n");
        d.text.push_str(npr_abi::OBJECT_HEAD_WGSL);
        self.param_fields(&mut d.text, ParamBinding::PerObject);
        d.text.push_str("}\n");
        if let PassKind::Compute { .. } = kind {
            // Every object's block at once, one stride-sized slot each; each
            // invocation copies its object's into `object`, so expressions
            // read `object` as in render passes.
            let stride = npr_abi::manifest::object_stride(self.alloc.object_uniform_size);
            let pad = (stride - self.alloc.object_uniform_size) / 16;
            d.text.push_str("struct NprObjectSlot {\n    o: Object,\n");
            if pad > 0 {
                let _ = writeln!(d.text, "    pad: array<vec4<f32>, {pad}>,");
            }
            let _ = writeln!(
                d.text,
                "}}\n@group(1) @binding(0) var<storage, read> npr_objects: array<NprObjectSlot>; // {stride} bytes apart\n\
                 @group(1) @binding(1) var<storage, read> npr_members: array<vec4<u32>>; // object, first vertex, vertices, first workgroup\n\
                 var<private> object: Object;"
            );
            return;
        }
        d.text.push_str("@group(1) @binding(0) var<uniform> object: Object;\n");
        let mut next1 = 1u32;
        for t in uses
            .textures
            .iter()
            .filter(|t| self.ir.textures[t.0 as usize].per_object)
        {
            let tex = &self.ir.textures[t.0 as usize];
            let _ = writeln!(
                d.text,
                "@group(1) @binding({next1}) var tex_{}: texture_2d<f32>; // per object",
                tex.name
            );
            d.object_bindings.push(Binding {
                binding: next1,
                resource: Resource::Texture { texture: t.0 as usize },
            });
            let _ = writeln!(
                d.text,
                "@group(1) @binding({}) var samp_{}: sampler;",
                next1 + 1,
                tex.name
            );
            d.object_bindings.push(Binding {
                binding: next1 + 1,
                resource: Resource::TextureSampler { texture: t.0 as usize },
            });
            next1 += 2;
        }
    }

    /// One `p_<name>: vec4<f32>` field per parameter bound as `which`; a
    /// gradient's slots as one array (`npr_abi::gradient`).
    fn param_fields(&self, text: &mut String, which: ParamBinding) {
        for (i, b) in self.bindings.iter().enumerate() {
            if *b == which {
                let p = &self.ir.params[i];
                match npr_abi::gradient::slots_of(&p.declared_type()) {
                    1 => {
                        let _ = writeln!(text, "    p_{}: vec4<f32>,", p.name);
                    }
                    n => {
                        let _ = writeln!(text, "    p_{}: array<vec4<f32>, {n}>,", p.name);
                    }
                }
            }
        }
    }
}

impl Declared {
    fn bind(&mut self, binding: u32, resource: Resource) {
        self.bindings.push(Binding { binding, resource });
    }
}
