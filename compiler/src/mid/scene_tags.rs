//! Tags a known scene does not have: a warning for every live pass that
//! draws or computes only objects of a tag no object in the scene carries.
//!
//! Such a pass runs over nothing, so its targets stay at their clear value
//! (and its per-object values at zero); that is allowed, because a style
//! may serve scenes with and without those objects, but it is usually a
//! misspelt tag. Passes the scene pruned (only read behind a false
//! `scene_has(tag)`) are not live and are not reported: that is the
//! intended way to skip them.

use crate::ir::{Ir, PassKind};
use crate::mid::prune::Live;
use npr_abi::SceneSummary;
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic};

/// W0402 for each live `render(tag)` / `compute(domain, tag)` / `lines(tag)` pass whose
/// tag `scene` lacks. Nothing without a scene.
pub fn absent_tags(ir: &Ir, live: &Live, scene: Option<&SceneSummary>) -> Vec<Diagnostic> {
    let Some(scene) = scene else { return Vec::new() };
    let mut diags = Vec::new();
    for pid in &live.passes {
        let pass = ir.pass(*pid);
        let tag = match &pass.kind {
            PassKind::Render { tag: Some(tag), .. } | PassKind::Compute { tag: Some(tag), .. } => tag,
            PassKind::Lines(lines) => match &lines.tag {
                Some(tag) => tag,
                None => continue,
            },
            _ => continue,
        };
        if scene.tags.contains(tag) {
            continue;
        }
        let verb = match pass.kind {
            PassKind::Render { .. } => "draws",
            PassKind::Lines(_) => "outlines",
            _ => "runs over",
        };
        let mut d = Diagnostic::warning(
            codes::ABSENT_TAG,
            format!("no object in scene {} is tagged `{tag}`", scene.name),
        )
        .with_primary(
            pass.name_span,
            format!("pass `{}` {verb} only objects tagged `{tag}`: none", pass.name),
        )
        .with_note("the pass runs over no object, so its targets keep their clear value");
        let tags: Vec<&str> = scene.tags.iter().map(String::as_str).collect();
        d = match did_you_mean(tag, tags.iter().copied()) {
            Some(s) => d.with_help(format!("did you mean `{s}`? the scene's tags are: {}", tags.join(", "))),
            None if tags.is_empty() => d.with_help(format!(
                "the scene's objects have no tags; give one `tags = [\"{tag}\"]`"
            )),
            None => d.with_help(format!(
                "the scene's tags are: {}; or give an object `tags = [\"{tag}\"]`",
                tags.join(", ")
            )),
        };
        diags.push(d);
    }
    diags
}
