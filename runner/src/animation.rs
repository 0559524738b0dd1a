//! Parameter values at run time: keyframe interpolation for animated
//! parameters, and the byte layout of the style and per-object uniform
//! blocks (one `vec4<f32>` slot per parameter, a gradient's several: see
//! the manifest and `npr_abi::gradient`).

use crate::scene::Object;
use npr_abi::manifest::{Manifest, ParamBinding, ParamManifest, OBJECT_PARAMS_OFFSET};
use npr_diag::{codes, Diagnostic};

/// Where `time_s` falls among `p`'s keyframes: the values before and
/// after it and the eased weight `u` of the second (0 at a key, before the
/// first and after the last; the default when there are no keyframes).
fn keyframe_pair(p: &ParamManifest, time_s: f64) -> (&[f64], &[f64], f64) {
    let keys = &p.keyframes;
    let (Some(first), Some(last)) = (keys.first(), keys.last()) else {
        return (&p.default, &p.default, 0.0);
    };
    if time_s <= first.0 {
        return (&first.1, &first.1, 0.0);
    }
    if time_s >= last.0 {
        return (&last.1, &last.1, 0.0);
    }
    let i = keys.iter().rposition(|(t, _)| *t <= time_s).unwrap_or(0);
    let (t0, v0) = &keys[i];
    let (t1, v1) = &keys[i + 1];
    let span = (t1 - t0).max(f64::MIN_POSITIVE);
    let mut u = ((time_s - t0) / span).clamp(0.0, 1.0);
    match p.interpolation.as_str() {
        "step" => u = 0.0,
        // Smoothstep easing 3u² − 2u³: zero velocity at each key.
        "smooth" => u = u * u * (3.0 - 2.0 * u),
        _ => {}
    }
    (v0, v1, u)
}

/// Component `j` of the value between `v0` and `v1` at weight `u`: `v0`'s
/// own at a key (so −0 and non-finite values pass unchanged), else
/// `a + (b − a)·u`; `None` past the value's components.
fn interpolated((v0, v1, u): (&[f64], &[f64], f64), j: usize) -> Option<f64> {
    let a = *v0.get(j)?;
    if u == 0.0 && std::ptr::eq(v0, v1) {
        return Some(a);
    }
    let b = *v1.get(j)?;
    Some(a + (b - a) * u)
}

/// Value of a parameter at `time_s` (keyframes, or the default).
pub fn value_at(p: &ParamManifest, time_s: f64) -> Vec<f64> {
    let pair = keyframe_pair(p, time_s);
    (0..).map_while(|j| interpolated(pair, j)).collect()
}

/// Up to four values as one vec4 slot (the missing components zero).
fn slot(values: impl IntoIterator<Item = f64>) -> [f32; 4] {
    let mut s = [0.0f32; 4];
    for (s, v) in s.iter_mut().zip(values) {
        *s = v as f32;
    }
    s
}

/// Component `x` of `p` as the shaders see it: a `%` of the image
/// `height` in pixels.
fn of_height(p: &ParamManifest, x: f64, height: u32) -> f64 {
    if p.default_percent_of_height {
        x / 100.0 * height as f64
    } else {
        x
    }
}

/// The first component of parameter `name` at `time_s` (keyframes, `%` of
/// the image `height`), as the shaders see it; `None` if the manifest has
/// no such parameter. What a `lines` pass's settings read on the CPU.
pub fn scalar_at(m: &Manifest, name: &str, time_s: f64, height: u32) -> Option<f64> {
    let p = m.params.iter().find(|p| p.name == name)?;
    interpolated(keyframe_pair(p, time_s), 0).map(|x| of_height(p, x, height))
}

/// The style uniform block at `time_s`, written over `out` (zeroed
/// first), which a renderer keeps from frame to frame; a parameter without
/// keyframes is read in place (only keyframed and height-relative ones are
/// computed).
pub fn write_style_params(m: &Manifest, time_s: f64, height: u32, out: &mut [u8]) {
    out.fill(0);
    for p in &m.params {
        write_style_param(p, time_s, height, out);
    }
}

/// The uniform parameters of `m` whose value changes with the time (they
/// have keyframes): what a frame writes again over a style block that
/// [`write_style_params`] wrote for the same parameters and height.
pub fn animated_style_param_indices(m: &Manifest) -> Vec<usize> {
    m.params
        .iter()
        .enumerate()
        .filter(|(_, p)| p.binding == ParamBinding::Uniform && p.offset.is_some() && !p.keyframes.is_empty())
        .map(|(i, _)| i)
        .collect()
}

/// Parameters `indices` of `m` at `time_s`, written over their slots of
/// the style block `out` (the other slots as they were).
pub fn write_style_params_at(m: &Manifest, indices: &[usize], time_s: f64, height: u32, out: &mut [u8]) {
    for p in indices.iter().filter_map(|&i| m.params.get(i)) {
        write_style_param(p, time_s, height, out);
    }
}

/// `p`'s slots of the style block at `time_s` (nothing for a parameter
/// that is not in the block).
fn write_style_param(p: &ParamManifest, time_s: f64, height: u32, out: &mut [u8]) {
    if p.binding != ParamBinding::Uniform {
        return;
    }
    let Some(off) = p.offset else { return };
    // Computed in place, component by component: a frame allocates nothing here.
    let pair = keyframe_pair(p, time_s);
    // One vec4 per slot; a gradient has several (`npr_abi::gradient`).
    let slots = npr_abi::gradient::slots_of(&p.ty);
    for k in 0..slots {
        let components = (k * 4..).map_while(|j| interpolated(pair, j));
        let bytes: [u8; 16] = bytemuck::cast(slot(components.map(|x| of_height(p, x, height))));
        let off = off as usize + k * 16;
        if off + 16 <= out.len() {
            out[off..off + 16].copy_from_slice(&bytes);
        }
    }
}

/// The indices in `m.params` of the per-object parameters that have a
/// slot: what [`write_object_params`] writes, found once per renderer (a
/// frame then reads only those parameters, not every one of the style's).
pub fn object_param_indices(m: &Manifest) -> Vec<usize> {
    m.params
        .iter()
        .enumerate()
        .filter(|(_, p)| p.binding == ParamBinding::PerObject && p.offset.is_some())
        .map(|(i, _)| i)
        .collect()
}

/// The per-object parameter slots (after the two matrices) for one object,
/// written over `out` (zeroed first), which a renderer keeps from frame to
/// frame: a frame allocates nothing for them. `indices` are
/// [`object_param_indices`] of the manifest `params` belong to. A binding
/// with the wrong number of components is reported (E0405).
pub fn write_object_params(
    params: &[ParamManifest],
    indices: &[usize],
    o: &Object,
    out: &mut [u8],
    diags: &mut Vec<Diagnostic>,
) {
    out.fill(0);
    for p in indices.iter().filter_map(|&i| params.get(i)) {
        let Some(off) = p.offset else { continue };
        let rgba: [f64; 4];
        let mut v: &[f64] = &p.default;
        // A scene's binding, else the object's glTF material under the
        // documented names (`gltf_material`), else the default.
        let material = o.material.as_ref().and_then(|m| m.value(&p.name));
        let from_material = !o.params.contains_key(&p.name) && material.is_some();
        let bound = o
            .params
            .get(&p.name)
            .map(Vec::as_slice)
            .or(material.as_ref().map(|(values, n)| &values[..*n]));
        let origin = if from_material {
            "'s glTF material gives"
        } else {
            " binds"
        };
        if let Some(bound) = bound {
            let n = p.components as usize;
            // A colour may be given as rgb; alpha defaults to 1.
            if bound.len() == n || (n == 4 && bound.len() == 3) {
                v = bound;
                if v.len() == 3 && n == 4 {
                    rgba = [bound[0], bound[1], bound[2], 1.0];
                    v = &rgba;
                }
                if let Some((lo, hi)) = p.range {
                    if let Some(bad) = v.iter().find(|x| **x < lo || **x > hi) {
                        let mut d = Diagnostic::error(
                            codes::OUT_OF_RANGE,
                            format!("object `{}`{origin} `{}` outside its range", o.name, p.name),
                        )
                        .with_help(format!("`{}` is declared in {lo}..{hi}", p.name));
                        if let Some(s) = o.param_spans.get(&p.name) {
                            d = d.with_primary(*s, format!("{bad} is outside {lo}..{hi}"));
                        }
                        diags.push(d);
                    }
                }
            } else {
                let mut d = Diagnostic::error(
                    codes::BAD_SCENE,
                    format!(
                        "object `{}`{origin} `{}` with {} value(s), expected {n}",
                        o.name,
                        p.name,
                        bound.len()
                    ),
                )
                .with_help(format!("`{}` is a {}", p.name, p.ty));
                if let Some(s) = o.param_spans.get(&p.name) {
                    d = d.with_primary(*s, "wrong number of components");
                }
                diags.push(d);
            }
        }
        put_object_slot(off, v, out);
    }
}

/// The per-object parameter slots of an object that binds none: every
/// slot's default, the bytes [`write_object_params`] writes for it, over
/// `len` bytes (an object block's params region). Made once per renderer:
/// a frame copies them for each such object instead of looking up each
/// parameter (docs/PERFORMANCE.md, "A host's frame").
pub fn object_param_defaults(params: &[ParamManifest], indices: &[usize], len: usize) -> Vec<u8> {
    let mut out = vec![0; len];
    for p in indices.iter().filter_map(|&i| params.get(i)) {
        if let Some(off) = p.offset {
            put_object_slot(off, &p.default, &mut out);
        }
    }
    out
}

/// `values` as the vec4 slot at block offset `offset` of an object's
/// params region `out` (which starts at `OBJECT_PARAMS_OFFSET`); a slot
/// past the region's end is left out.
fn put_object_slot(offset: u64, values: &[f64], out: &mut [u8]) {
    let start = (offset - OBJECT_PARAMS_OFFSET) as usize;
    if start + 16 <= out.len() {
        let bytes: [u8; 16] = bytemuck::cast(slot(values.iter().copied()));
        out[start..start + 16].copy_from_slice(&bytes);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn param(keys: Vec<(f64, Vec<f64>)>, interpolation: &str) -> ParamManifest {
        ParamManifest {
            name: "glow".into(),
            doc: String::new(),
            ty: "float".into(),
            unit: String::new(),
            components: 1,
            default: vec![0.2],
            default_percent_of_height: false,
            range: Some((0.0, 1.0)),
            enum_variants: vec![],
            keyframes: keys,
            interpolation: interpolation.into(),
            binding: ParamBinding::Uniform,
            offset: Some(0),
        }
    }

    #[test]
    fn keyframes_interpolate_exactly() {
        let p = param(vec![(0.0, vec![0.1]), (8.0, vec![0.3])], "linear");
        assert_eq!(value_at(&p, -1.0), vec![0.1]);
        assert!((value_at(&p, 4.0)[0] - 0.2).abs() < 1e-12);
        assert!((value_at(&p, 2.0)[0] - 0.15).abs() < 1e-12);
        assert_eq!(value_at(&p, 9.0), vec![0.3]);
        let s = param(vec![(0.0, vec![0.1]), (8.0, vec![0.3])], "step");
        assert_eq!(value_at(&s, 7.9), vec![0.1]);
        let e = param(vec![(0.0, vec![0.0]), (1.0, vec![1.0])], "smooth");
        assert!((value_at(&e, 0.25)[0] - 0.15625).abs() < 1e-12);
    }

    /// The bytes copied for an object that binds no param are the ones
    /// `write_object_params` writes for it: every slot's default (scalars,
    /// vectors, colours), nothing for a param without a slot, nothing past
    /// the region's end, zero between.
    #[test]
    fn object_defaults_are_what_an_object_without_bindings_is_written() {
        let object_param = |name: &str, components: u32, default: Vec<f64>, slot: Option<u64>| ParamManifest {
            name: name.into(),
            components,
            default,
            range: None,
            binding: ParamBinding::PerObject,
            offset: slot.map(|k| OBJECT_PARAMS_OFFSET + 16 * k),
            ..param(vec![], "linear")
        };
        let params = vec![
            param(vec![], "linear"),
            object_param("breakup", 1, vec![0.75], Some(0)),
            object_param("tint", 4, vec![0.1, 0.2, 0.3, 1.0], Some(3)),
            object_param("offset", 3, vec![-1.0, 2.5, 1e-3], Some(1)),
            object_param("lit_map", 4, vec![], None),
            object_param("far", 2, vec![3.0, 4.0], Some(7)),
        ];
        let indices = [1, 2, 3, 4, 5];
        // Slots 0 to 3; slot 7 lies past the region, slot 2 is padding.
        let len = 16 * 4;
        let defaults = object_param_defaults(&params, &indices, len);
        let cube = std::sync::Arc::new(crate::scene::primitives::cube(1.0));
        let object = Object::plain("o", &cube, glam::Mat4::IDENTITY, &[]);
        let mut written = vec![0xab; len];
        let mut diags = Vec::new();
        write_object_params(&params, &indices, &object, &mut written, &mut diags);
        assert!(diags.is_empty());
        assert_eq!(defaults, written);
        let floats: Vec<f32> = defaults
            .chunks_exact(4)
            .map(|b| f32::from_ne_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        #[rustfmt::skip]
        let expected = [
            0.75, 0.0, 0.0, 0.0,
            -1.0, 2.5, 1e-3, 0.0,
            0.0, 0.0, 0.0, 0.0,
            0.1, 0.2, 0.3, 1.0,
        ];
        assert_eq!(floats, expected);
    }

    #[test]
    fn no_keyframes_gives_default() {
        assert_eq!(value_at(&param(vec![], "linear"), 3.0), vec![0.2]);
    }
}
