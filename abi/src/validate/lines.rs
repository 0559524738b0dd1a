//! Checks of a `lines` pass in a manifest read from disk: its crease
//! thresholds are angles, its line sets select something under distinct
//! names, its shape settings are finite and name only
//! parameters the manifest has (as plain numbers the runner can read on the
//! CPU), and its constant parts are inside the ranges the runner builds
//! strips for.

use super::{bad, Invalid};
use crate::lines::{LineScalar, MAX_LINE_WIDTH_PX, MAX_TAPER};
use crate::manifest::*;

impl Manifest {
    pub(super) fn validate_lines(&self, field: &str, p: &PassManifest) -> Result<(), Invalid> {
        let PassKindManifest::Lines { edges, shape, sets, .. } = &p.kind else {
            return Ok(());
        };
        let f = format!("{field}.kind");
        validate_crease(&format!("{f}.edges.crease_deg"), edges.crease_deg)?;
        self.validate_line_shape(&f, shape)?;
        for (k, set) in sets.iter().enumerate() {
            let sf = format!("{f}.sets[{k}]");
            if set.edges.is_empty() {
                return bad(format!("{sf}.edges"), "selects no edge type");
            }
            if sets[..k].iter().any(|s| s.name == set.name) {
                return bad(format!("{sf}.name"), format!("`{}` names two sets", set.name));
            }
            validate_crease(&format!("{sf}.edges.crease_deg"), set.edges.crease_deg)?;
            self.validate_line_shape(&sf, &set.shape)?;
        }
        Ok(())
    }

    fn validate_line_shape(&self, f: &str, shape: &crate::lines::LineShape) -> Result<(), Invalid> {
        for (name, s) in shape.named() {
            self.validate_line_scalar(&format!("{f}.shape.{name}"), s)?;
        }
        let constant_only = |s: &LineScalar| s.params.is_empty() && s.per_second == 0.0;
        if constant_only(&shape.width) && !(0.0..=MAX_LINE_WIDTH_PX).contains(&shape.width.constant) {
            return bad(
                format!("{f}.shape.width"),
                format!("{} px is outside 0..={MAX_LINE_WIDTH_PX}", shape.width.constant),
            );
        }
        if constant_only(&shape.taper) && !(0.0..=MAX_TAPER).contains(&shape.taper.constant) {
            return bad(
                format!("{f}.shape.taper"),
                format!("{} is outside 0..={MAX_TAPER}", shape.taper.constant),
            );
        }
        Ok(())
    }

    fn validate_line_scalar(&self, field: &str, s: &LineScalar) -> Result<(), Invalid> {
        if !s.is_finite() {
            return bad(field, "not finite");
        }
        for (k, t) in s.params.iter().enumerate() {
            let Some(param) = self.params.iter().find(|p| p.name == t.param) else {
                return bad(format!("{field}.params[{k}]"), format!("no param `{}`", t.param));
            };
            if param.components != 1 || !param.enum_variants.is_empty() {
                return bad(
                    format!("{field}.params[{k}]"),
                    format!("param `{}` is not a plain number", t.param),
                );
            }
            if param.binding == ParamBinding::PerObject {
                return bad(
                    format!("{field}.params[{k}]"),
                    format!("param `{}` is per object; a lines setting is per pass", t.param),
                );
            }
        }
        Ok(())
    }
}

/// A crease threshold is a dihedral angle in 0..=180°.
fn validate_crease(field: &str, deg: Option<f64>) -> Result<(), Invalid> {
    match deg {
        Some(deg) if !(0.0..=180.0).contains(&deg) => bad(field, format!("{deg} is outside 0..=180 degrees")),
        _ => Ok(()),
    }
}
