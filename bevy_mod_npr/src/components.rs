//! The components a Bevy app puts on its entities: [`NprStyle`] on a
//! camera (which style draws it), [`NprParams`] beside it (the style's
//! parameters, editable at run time and through reflection), [`NprObject`]
//! on a mesh entity (its tags and per-object params) and [`NprLight`] on
//! the entity whose rotation gives the style's `light`.

use crate::asset::NprStyleAsset;
use bevy::prelude::*;
use std::collections::BTreeMap;

/// On a `Camera3d`: the camera's image is drawn by this style, from the
/// visible `Mesh3d` entities (with their [`NprObject`] tags and params),
/// replacing what Bevy drew. A style that has not loaded (or never
/// compiled) leaves the camera's image as Bevy drew it; a later broken
/// save keeps the last style that compiled.
#[derive(Component, Clone, Debug)]
#[require(NprParams)]
pub struct NprStyle(pub Handle<NprStyleAsset>);

/// The camera's style parameters by name, written as `npr render --set`
/// takes them (`"5"`, `"2px"`, `"#ff8800"`, `"true"`, `"30deg"`). Change
/// them at any time (or with an inspector: the component is reflected);
/// a value the style refuses (an unknown name E0101, a wrong type E0201,
/// unit E0202 or range E0203) is logged once and the parameter keeps its
/// previous value. The style's `.npr` file is compiled with its
/// parameters kept as uniforms, so every one can change.
#[derive(Component, Clone, Debug, Default, Reflect, PartialEq)]
#[reflect(Component, Default)]
pub struct NprParams {
    pub values: BTreeMap<String, String>,
}

impl NprParams {
    /// With `name` set to `value`.
    pub fn with(mut self, name: &str, value: impl ToString) -> NprParams {
        self.set(name, value);
        self
    }

    /// Set `name` to `value` (from the next frame on).
    pub fn set(&mut self, name: &str, value: impl ToString) {
        self.values.insert(name.to_string(), value.to_string());
    }
}

/// On a `Mesh3d` entity: its tags (for a style's `render(scene, tag: ...)`,
/// `lines(tag)` and `compute(objects, tag)` passes) and its values of the
/// style's `object param`s. An entity without one is drawn untagged with
/// the params' defaults.
#[derive(Component, Clone, Debug, Reflect, PartialEq)]
#[reflect(Component, Default)]
pub struct NprObject {
    pub tags: Vec<String>,
    /// Per `object param`: 1 component for a number or boolean, N for a
    /// vector, 4 for a colour (its sRGB components, as the style's colour
    /// literals and a scene's `"#rrggbb"` are written).
    pub params: BTreeMap<String, Vec<f64>>,
    /// Whether `view(light)` passes (shadow maps) draw it.
    pub casts_shadows: bool,
}

impl Default for NprObject {
    fn default() -> NprObject {
        NprObject {
            tags: Vec::new(),
            params: BTreeMap::new(),
            casts_shadows: true,
        }
    }
}

impl NprObject {
    /// An object with one tag.
    pub fn tagged(tag: &str) -> NprObject {
        NprObject::default().and_tagged(tag)
    }

    /// With `tag` added.
    pub fn and_tagged(mut self, tag: &str) -> NprObject {
        self.tags.push(tag.to_string());
        self
    }

    /// With the per-object param `name` set to `value`.
    pub fn with(mut self, name: &str, value: impl Into<NprValue>) -> NprObject {
        self.params.insert(name.to_string(), value.into().0);
        self
    }
}

/// A per-object param's value: what [`NprObject::with`] takes.
#[derive(Clone, Debug, PartialEq)]
pub struct NprValue(pub Vec<f64>);

impl From<f64> for NprValue {
    fn from(v: f64) -> NprValue {
        NprValue(vec![v])
    }
}

impl From<f32> for NprValue {
    fn from(v: f32) -> NprValue {
        NprValue(vec![v as f64])
    }
}

impl From<bool> for NprValue {
    fn from(v: bool) -> NprValue {
        NprValue(vec![if v { 1.0 } else { 0.0 }])
    }
}

impl From<Vec2> for NprValue {
    fn from(v: Vec2) -> NprValue {
        NprValue(v.to_array().iter().map(|&c| c as f64).collect())
    }
}

impl From<Vec3> for NprValue {
    fn from(v: Vec3) -> NprValue {
        NprValue(v.to_array().iter().map(|&c| c as f64).collect())
    }
}

impl From<Vec4> for NprValue {
    fn from(v: Vec4) -> NprValue {
        NprValue(v.to_array().iter().map(|&c| c as f64).collect())
    }
}

impl From<Color> for NprValue {
    /// The colour's sRGB components and alpha: a style's `#rrggbb` is
    /// its bytes / 255 (docs/decisions/0003).
    fn from(c: Color) -> NprValue {
        NprValue(c.to_srgba().to_f32_array().iter().map(|&c| c as f64).collect())
    }
}

/// The style's key light (`light.dir`, `light.color`): on an entity whose
/// transform points its forward (-Z) axis along the light's rays, as
/// Bevy's `DirectionalLight`. The first one found is the key light, the
/// next three `light2` … `light4`. Without one, the style gets npr's
/// default light (from above, right and in front).
#[derive(Component, Clone, Debug, Reflect, PartialEq)]
#[reflect(Component, Default)]
#[require(Transform)]
pub struct NprLight {
    /// Written as the style's colour literals: sRGB components.
    pub color: Color,
    pub intensity: f32,
}

impl Default for NprLight {
    fn default() -> NprLight {
        NprLight {
            color: Color::WHITE,
            intensity: 1.0,
        }
    }
}
