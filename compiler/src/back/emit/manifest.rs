//! Assemble `manifest.json` from the IR, the allocation and the emitted passes.

use crate::back::allocate::Allocation;
use crate::back::emit::EmittedPass;
use crate::ir::*;
use crate::mid::consteval::const_eval;
use crate::mid::prune::Live;
use crate::InternalError;
use npr_abi::manifest::*;
use npr_diag::SourceMap;

#[allow(clippy::too_many_arguments)]
pub fn build(
    ir: &Ir,
    live: &Live,
    alloc: &Allocation,
    bindings: &[ParamBinding],
    emitted: &[(PassId, EmittedPass)],
    sources: &SourceMap,
    source_name: &str,
    filters: &std::collections::BTreeMap<String, npr_abi::FilterProgram>,
) -> Result<Manifest, InternalError> {
    let targets = alloc
        .targets
        .iter()
        .map(|(t, phys)| {
            let pass = ir.pass(t.pass);
            TargetManifest {
                name: ir.target_name(*t),
                format: pass.outputs[t.output as usize].format,
                scale: pass.scale,
                physical: *phys,
            }
        })
        .collect();
    let mut attributes: Vec<Attribute> = Vec::new();
    let passes = emitted
        .iter()
        .map(|(pid, e)| {
            let pass = ir.pass(*pid);
            for a in &e.attributes {
                if !attributes.contains(a) {
                    attributes.push(*a);
                }
            }
            let outputs = (0..pass.outputs.len())
                .filter_map(|i| {
                    alloc.target_index(TargetRef {
                        pass: *pid,
                        output: i as u32,
                    })
                })
                .collect();
            Ok(PassManifest {
                name: pass.name.clone(),
                kind: match &pass.kind {
                    PassKind::Render { tag, view, depth, .. } => PassKindManifest::Render {
                        tag: tag.clone(),
                        light_view: *view == PassView::Light,
                        attributes: e.attributes.clone(),
                        depth: depth_mode(*pid, *depth, live, emitted)?,
                        vertex_entry: "vs_main".into(),
                        fragment_entry: "fs_main".into(),
                    },
                    PassKind::Image { .. } if ir.tiled.contains_key(pid) => PassKindManifest::TiledImage {
                        entry: super::tiled::TILED_ENTRY.into(),
                    },
                    PassKind::Image { .. } => PassKindManifest::Image {
                        vertex_entry: "vs_main".into(),
                        fragment_entry: "fs_main".into(),
                    },
                    PassKind::Compute {
                        domain,
                        tag,
                        key,
                        samples,
                        values,
                    } => compute_kind(ir, alloc, *pid, (*domain, *key, *samples), tag, values, e)?,
                    PassKind::Lines(lines) => PassKindManifest::Lines {
                        tag: lines.tag.clone(),
                        edges: lines.edges,
                        shape: line_shape(ir, &lines.shape)?,
                        sets: lines
                            .sets
                            .iter()
                            .map(|set| {
                                Ok(npr_abi::lines::LineSet {
                                    name: set.name.clone(),
                                    tag: set.tag.clone(),
                                    edges: set.edges,
                                    shape: line_shape(ir, &set.shape)?,
                                    priority: set.priority,
                                    visibility: set.visibility,
                                    dash: set.dash,
                                })
                            })
                            .collect::<Result<Vec<_>, InternalError>>()?,
                        depth: depth_mode(*pid, lines.depth, live, emitted)?,
                        vertex_entry: "vs_main".into(),
                        fragment_entry: "fs_main".into(),
                    },
                },
                scale: pass.scale,
                shader: format!("{}.wgsl", pass.name),
                blend: blend_modes(pass, *pid, alloc),
                outputs,
                clear: pass.clear,
                bindings: e.bindings.clone(),
                object_bindings: e.object_bindings.clone(),
                line: sources.line_col(pass.name_span.file, pass.name_span.start).0,
                device_half_rounding: e.device_half_rounding,
            })
        })
        .collect::<Result<Vec<_>, InternalError>>()?;
    attributes.sort();
    let textures = ir
        .textures
        .iter()
        .map(|t| {
            Ok(TextureManifest {
                name: t.name.clone(),
                source: texture_source(t, filters)?,
                per_object: t.per_object,
                wrap_repeat: t.wrap_repeat,
                filter_linear: t.filter_linear,
                mips: t.mips,
            })
        })
        .collect::<Result<Vec<_>, InternalError>>()?;
    let params = ir
        .params
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let d = ir.expr(p.default);
            let (default, percent) = match &d.kind {
                ExprKind::PercentOfHeight(f) => (vec![*f * 100.0], true),
                _ => (
                    const_eval(ir, p.default).map(|c| c.as_f64s()).unwrap_or_default(),
                    false,
                ),
            };
            let variants = match &p.ty {
                ParamTy::Enum(v) => v.clone(),
                _ => Vec::new(),
            };
            ParamManifest {
                name: p.name.clone(),
                doc: p.doc.clone(),
                ty: p.declared_type(),
                unit: p.unit.name().to_string(),
                // A gradient's value is its slots, four components each.
                components: if p.ty == ParamTy::Gradient {
                    4
                } else {
                    p.value_ty.components().unwrap_or(1)
                },
                default,
                default_percent_of_height: percent,
                range: p.range,
                enum_variants: variants,
                keyframes: p.keys.iter().map(|k| (k.time_s, k.value.clone())).collect(),
                interpolation: p.interpolation.clone(),
                binding: bindings[i],
                offset: alloc.param_offsets.get(&ParamId(i as u32)).copied(),
            }
        })
        .collect();
    // Resolve refuses a style without `output`, and prune keeps the output
    // live, so the allocator gave it a target: anything else is a bug.
    let output = ir
        .output
        .and_then(|o| alloc.target_index(o))
        .ok_or_else(|| InternalError {
            message: "the output target has no allocated target".into(),
            detail: match ir.output {
                Some(o) => format!("`{}` is not among the allocated targets", ir.target_name(o)),
                None => "the IR has no output".into(),
            },
            span: Some(ir.output_span),
            wgsl: None,
        })?;
    Ok(Manifest {
        version: MANIFEST_VERSION,
        style: ir.style_name.clone(),
        source: source_name.to_string(),
        passes,
        targets,
        physical: alloc.physical.clone(),
        textures,
        params,
        style_uniform_size: alloc.style_uniform_size,
        object_uniform_size: alloc.object_uniform_size,
        scene_attributes: attributes,
        output,
        // Filled in once naga has validated the shaders (`back::device_needs`).
        device_needs: Vec::new(),
    })
}

/// The manifest kind of a live compute pass: its live values in slot order.
fn compute_kind(
    ir: &Ir,
    alloc: &Allocation,
    pid: PassId,
    (domain, key, samples): (ComputeDomain, Option<ExprId>, Option<SampleSpec>),
    tag: &Option<String>,
    values: &[ObjectValue],
    e: &EmittedPass,
) -> Result<PassKindManifest, InternalError> {
    use crate::back::emit::compute::{ELEMENTS_ENTRY, REDUCE_OBJECTS_ENTRY, UPDATE_OBJECTS_ENTRY};
    let mut slots: Vec<(u32, ValueSlot)> = values
        .iter()
        .enumerate()
        .filter_map(|(i, v)| {
            let packed = alloc.value_slots.get(&(pid, i as u32))?;
            Some((
                *packed,
                ValueSlot {
                    name: v.name.clone(),
                    ty: v.ty.describe().to_string(),
                    kind: match v.rule {
                        ValueRule::Reduce(op) => ValueKind::Reduce(op),
                        ValueRule::Out => ValueKind::Out,
                        ValueRule::State => ValueKind::State,
                    },
                },
            ))
        })
        .collect();
    slots.sort_by_key(|(p, _)| *p);
    // The ID target a pass over pixels runs over: the logical target its
    // key reads (live, since the pass's values read it).
    let pixels_of = match (domain, key.map(|k| &ir.expr(k).kind)) {
        (ComputeDomain::Pixels, Some(ExprKind::Target { target, .. })) => {
            Some(alloc.target_index(*target).ok_or_else(|| InternalError {
                message: format!("the ID target of pass `{}` was not allocated", ir.pass(pid).name),
                detail: format!("`{}` is not among the allocated targets", ir.target_name(*target)),
                span: Some(ir.pass(pid).name_span),
                wgsl: None,
            })?)
        }
        (ComputeDomain::Pixels, _) => {
            return Err(InternalError {
                message: format!("pass `{}` over pixels has no ID target read", ir.pass(pid).name),
                detail: "resolve gives every pass over pixels the read of its ID target".into(),
                span: Some(ir.pass(pid).name_span),
                wgsl: None,
            })
        }
        _ => None,
    };
    let has_elements = domain.has_elements();
    Ok(PassKindManifest::Compute {
        domain,
        tag: tag.clone(),
        attributes: e.attributes.clone(),
        values: slots.into_iter().map(|(_, s)| s).collect(),
        history: alloc.keeps_state(ir, pid),
        elements_entry: has_elements.then(|| ELEMENTS_ENTRY.to_string()),
        pixels_of,
        samples,
        objects_entry: if has_elements {
            REDUCE_OBJECTS_ENTRY
        } else {
            UPDATE_OBJECTS_ENTRY
        }
        .to_string(),
    })
}
/// The blend mode of each live output, in `@location` order; empty when all
/// replace, so that manifests of styles without blending are unchanged.
fn blend_modes(pass: &Pass, pid: PassId, alloc: &Allocation) -> Vec<Blend> {
    let modes: Vec<Blend> = (0..pass.outputs.len())
        .filter(|i| {
            alloc
                .target_index(TargetRef {
                    pass: pid,
                    output: *i as u32,
                })
                .is_some()
        })
        .map(|i| pass.outputs[i].blend)
        .collect();
    if modes.iter().all(|b| *b == Blend::Replace) {
        Vec::new()
    } else {
        modes
    }
}

/// The manifest's depth mode of a render pass: a kept depth that no live
/// pass tests against is not kept (nothing would read it), and a test names
/// the tested pass by its index among the emitted passes.
/// A lines pass's settings as the runner evaluates them; typecheck has
/// refused every setting that is not affine, so a failure is internal.
fn line_shape(ir: &Ir, shape: &LineSettings) -> Result<npr_abi::lines::LineShape, InternalError> {
    let fold = |id: ExprId| {
        crate::front::line_settings::affine(ir, id).map_err(|e| InternalError {
            message: "a lines setting is not affine after typecheck".into(),
            detail: e.label,
            span: Some(e.span),
            wgsl: None,
        })
    };
    Ok(npr_abi::lines::LineShape {
        width: fold(shape.width)?,
        amplitude: fold(shape.amplitude)?,
        wavelength: fold(shape.wavelength)?,
        phase: fold(shape.phase)?,
        taper: fold(shape.taper)?,
    })
}

fn depth_mode(
    pid: PassId,
    depth: PassDepth,
    live: &Live,
    emitted: &[(PassId, EmittedPass)],
) -> Result<DepthMode, InternalError> {
    Ok(match depth {
        PassDepth::Own => DepthMode::Own,
        PassDepth::Keep if live.depth.contains(&pid) => DepthMode::Keep,
        PassDepth::Keep => DepthMode::Own,
        PassDepth::Test {
            against: TestedDepth::Input(texture),
            bias_px,
            ..
        } => DepthMode::TestInput {
            // Every texture is emitted, in IR order.
            input: texture.0 as usize,
            bias_px,
        },
        PassDepth::Test {
            against: TestedDepth::Pass(pass),
            bias_px,
            span,
            ..
        } => {
            // Prune keeps every pass a live pass tests against.
            let index = emitted
                .iter()
                .position(|(p, _)| *p == pass)
                .ok_or_else(|| InternalError {
                    message: "a depth test names a pass that was not emitted".into(),
                    detail: format!("pass #{} is tested against but not live", pass.0),
                    span: Some(span),
                    wgsl: None,
                })?;
            DepthMode::Test { pass: index, bias_px }
        }
    })
}

/// A texture's source as the runner builds it; an art-map carries its
/// compiled filter.
fn texture_source(
    t: &Texture,
    filters: &std::collections::BTreeMap<String, npr_abi::FilterProgram>,
) -> Result<TextureSourceManifest, InternalError> {
    Ok(match &t.source {
        TextureSource::Image { path, resolved, srgb } => TextureSourceManifest::Image {
            path: path.clone(),
            resolved: resolved.clone(),
            srgb: *srgb,
        },
        TextureSource::Noise(spec) => TextureSourceManifest::Noise(*spec),
        TextureSource::HalftoneTable(spec) => TextureSourceManifest::HalftoneTable(*spec),
        TextureSource::FilterInput => TextureSourceManifest::FilterInput,
        TextureSource::Input(kind) => TextureSourceManifest::Input(npr_abi::InputSpec { kind: *kind }),
        TextureSource::Artmap {
            path,
            resolved,
            srgb,
            filter,
            levels,
            rip,
            ..
        } => TextureSourceManifest::Artmap(npr_abi::ArtmapSpec {
            path: path.clone(),
            resolved: resolved.clone(),
            srgb: *srgb,
            filter: filters.get(filter).cloned().ok_or_else(|| InternalError {
                message: format!("the filter of art-map `{}` was not compiled", t.name),
                detail: "pipeline::compile_filters compiles every art-map's filter".into(),
                span: Some(t.span),
                wgsl: None,
            })?,
            levels: *levels,
            rip: *rip,
        }),
    })
}
