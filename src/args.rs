//! Checks of command-line values that clap's types cannot express: an eye
//! the scene has, and `texgen`'s ranges (sizes, frame counts, times and
//! frame rates are `npr_diag::sizes`, shared with the libraries). Each failure is a diagnostic with a
//! code (E0502 for a value outside its domain, E0404 for a limit), which the
//! CLI prints and exits 1 with, before any work starts.
//!
//! The syntax of `--size WxH` is checked by clap's value parser
//! (`npr_diag::sizes::parse_size`); what it refuses is a usage error (E0501,
//! `usage.rs`).

use npr_diag::codes;
use npr_diag::Diagnostic;

fn bad_value(message: String, help: &str) -> Diagnostic {
    Diagnostic::error(codes::BAD_ARGUMENT_VALUE, message).with_help(help)
}

/// `--eye` against the scene's camera: 0 always, 1 only when it is stereo.
pub fn check_eye(eye: u32, stereo_camera: bool) -> Result<(), Diagnostic> {
    match (eye, stereo_camera) {
        (0, _) | (1, true) => Ok(()),
        (1, false) => Err(bad_value(
            "--eye 1: the scene's camera is mono, so it has only eye 0".into(),
            "give the scene's [camera] an `ipd` (e.g. `ipd = 0.064`) to make it stereo",
        )),
        (e, _) => Err(bad_value(
            format!("--eye {e}: eyes are 0 (left) and 1 (right, stereo cameras only)"),
            "use --eye 0 or --eye 1",
        )),
    }
}

/// `npr texgen`'s numeric arguments (`paint` maps use only the size).
pub fn check_texgen(size: u32, channels: u32, octaves: u32, frequency: u32, paint: bool) -> Result<(), Diagnostic> {
    let max = npr_abi::NoiseSpec::MAX_SIZE;
    if !(1..=max).contains(&size) {
        return Err(bad_value(
            format!("--size {size}: a generated texture is 1 to {max} texels wide"),
            "textures tile, so a small one repeated is usually enough",
        ));
    }
    if paint {
        return Ok(());
    }
    let max_octaves = npr_abi::NoiseSpec::MAX_OCTAVES;
    if !(1..=4).contains(&channels) {
        return Err(bad_value(
            format!("--channels {channels}: noise has 1 to 4 channels"),
            "1 is grey, 2 a warp-vector field in r, g",
        ));
    }
    if !(1..=max_octaves).contains(&octaves) {
        return Err(bad_value(
            format!("--octaves {octaves}: noise has 1 to {max_octaves} octaves"),
            "each octave halves the feature size",
        ));
    }
    if frequency == 0 {
        return Err(bad_value(
            "--frequency 0: the first octave needs at least 1 lattice cell".into(),
            "the default is 4",
        ));
    }
    Ok(())
}

/// `npr texgen --kind`.
pub fn texgen_kind(kind: &str) -> Result<TexgenKind, Diagnostic> {
    match kind {
        "gradient" => Ok(TexgenKind::Noise { gradient: true }),
        "value" => Ok(TexgenKind::Noise { gradient: false }),
        "paint" => Ok(TexgenKind::Paint),
        other => Err(bad_value(
            format!("unknown texture kind `{other}`"),
            "use --kind gradient, value or paint",
        )),
    }
}

/// What `npr texgen --kind` generates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TexgenKind {
    Noise { gradient: bool },
    Paint,
}

/// `npr texgen --kind paint --color "#rrggbb"`.
pub fn paint_color(color: Option<&str>) -> Result<[f64; 3], Diagnostic> {
    let parsed = color.and_then(npr_runner::texgen::parse_hex);
    parsed.ok_or_else(|| match color {
        None => bad_value(
            "`--kind paint` needs `--color \"#rrggbb\"`".into(),
            "the paint map varies around that base colour",
        ),
        Some(c) => bad_value(
            format!("--color {c}: expected a colour `#rrggbb`"),
            "six hex digits after `#`, e.g. \"#e9c48a\"",
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_outside_their_domain_are_refused_with_a_code() {
        assert!(check_eye(0, false).is_ok() && check_eye(1, true).is_ok());
        assert!(check_eye(1, false).is_err() && check_eye(2, true).is_err());
    }
}
