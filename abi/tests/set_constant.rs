//! `ParamManifest::set_constant`: what a run-time setting of a parameter
//! (a host's `set_param`, a sweep, the studio) leaves in the manifest.

use npr_abi::manifest::{ParamBinding, ParamManifest};
use npr_abi::ParamOverride;

/// An animated length parameter whose default was written in `%`.
fn animated_length() -> ParamManifest {
    ParamManifest {
        name: "width".into(),
        doc: String::new(),
        ty: "px".into(),
        unit: "px".into(),
        components: 1,
        default: vec![2.0],
        default_percent_of_height: true,
        range: Some((0.0, 100.0)),
        enum_variants: Vec::new(),
        keyframes: vec![(0.0, vec![1.0]), (2.0, vec![3.0])],
        interpolation: "linear".into(),
        binding: ParamBinding::Uniform,
        offset: Some(0),
    }
}

#[test]
fn a_set_value_is_a_constant_in_the_unit_it_was_typed_in() {
    let mut p = animated_length();
    p.set_constant(&ParamOverride {
        name: "width".into(),
        value: vec![4.0],
        percent_of_height: false,
    });
    // 4 px, not 4 % of the height as the old default's flag would say; no keyframe left.
    assert_eq!((p.default.as_slice(), p.default_percent_of_height), (&[4.0][..], false));
    assert!(p.keyframes.is_empty(), "{:?}", p.keyframes);
    p.set_constant(&ParamOverride {
        name: "width".into(),
        value: vec![5.0],
        percent_of_height: true,
    });
    assert_eq!((p.default.as_slice(), p.default_percent_of_height), (&[5.0][..], true));
    // Nothing else changes.
    let untouched = ParamManifest {
        default: p.default.clone(),
        default_percent_of_height: true,
        keyframes: Vec::new(),
        ..animated_length()
    };
    assert_eq!(p, untouched);
}
