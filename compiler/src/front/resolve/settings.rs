//! Resolve the settings of passes and outputs that name modes rather than
//! values: an output's `{ blend: mode }`, a render pass's `depth: keep` /
//! `depth: test(pass, bias: ...)`, and an image pass's `schedule: naive |
//! auto | tiled`. Whether a tested pass keeps its depth, and has the
//! tester's size and view, is checked once every pass is resolved
//! (`typecheck`); whether a pass forced `tiled` can be tiled, once it is
//! scheduled (`schedule`).

use super::{Resolver, Symbol};
use crate::ir::*;
use crate::schedule::Schedule;
use npr_abi::manifest::Blend;
use npr_abi::{Format, InputKind};
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic, Span};
use npr_dsl::ast::{self, ExprKind as AK, UnitSuffix};

impl Resolver<'_> {
    /// `out name: format = value { blend: mode }`: the only output setting.
    pub(super) fn output_blend(&mut self, o: &ast::OutputTarget, format: Format) -> Blend {
        let mut blend = Blend::Replace;
        let modes = || Blend::ALL.iter().map(|(n, _)| *n);
        for s in &o.settings {
            if s.key.name != "blend" {
                let mut d = Diagnostic::error(codes::BAD_ARGUMENT, format!("unknown output setting `{}`", s.key.name))
                    .with_primary(s.key.span, "not an output setting");
                d = match did_you_mean(&s.key.name, ["blend"]) {
                    Some(k) => d.with_help(format!("did you mean `{k}`?")),
                    None => d.with_help("outputs take one setting: `{ blend: over }`"),
                };
                self.error(d);
                continue;
            }
            let name = match &s.value.kind {
                AK::Name(n) => n.name.as_str(),
                _ => "",
            };
            let Some(b) = Blend::parse(name) else {
                let mut d = Diagnostic::error(
                    codes::BAD_ARGUMENT,
                    if name.is_empty() {
                        "`blend` takes a mode name".to_string()
                    } else {
                        format!("unknown blend mode `{name}`")
                    },
                )
                .with_primary(s.value.span, "not a blend mode");
                let list = modes().collect::<Vec<_>>().join(", ");
                d = match did_you_mean(name, modes()) {
                    Some(m) => d.with_help(format!("did you mean `{m}`? The modes are {list}")),
                    None => d.with_help(format!("the blend modes are {list}")),
                };
                self.error(d);
                continue;
            };
            if b != Blend::Replace && !format.is_blendable() {
                self.error(
                    Diagnostic::error(
                        codes::NOT_BLENDABLE,
                        format!("cannot blend into a {} target", format.name()),
                    )
                    .with_primary(
                        s.key.span.to(s.value.span),
                        format!("`{}` blending asked for here", b.name()),
                    )
                    .with_secondary(o.format.span, format!("{} cannot be blended", format.name()))
                    .with_help(
                        "32-bit float formats cannot be blended; use a 16-bit float or unorm format \
                         (rgba16float, rgba8unorm), or combine the values in a later image pass",
                    ),
                );
                continue;
            }
            blend = b;
        }
        blend
    }

    /// `depth: keep` and `depth: test(pass, bias: 2px | 0.001)` of a render
    /// pass. Whether the tested pass keeps its depth, and has this pass's
    /// size and view, is checked once every pass is resolved (typecheck).
    pub(super) fn depth_setting(&mut self, kind: &mut PassKind, s: &ast::Setting, seen: &mut Option<Span>) {
        if let Some(first) = *seen {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "`depth` is set twice")
                    .with_primary(s.key.span.to(s.value.span), "second `depth`")
                    .with_secondary(first, "first `depth`")
                    .with_help("a pass either keeps its depth or tests against another pass's"),
            );
            return;
        }
        *seen = Some(s.key.span.to(s.value.span));
        let is_lines = matches!(kind, PassKind::Lines(_));
        let (PassKind::Render { depth, .. } | PassKind::Lines(LinesKind { depth, .. })) = kind else {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "`depth` is a setting of render and lines passes")
                    .with_primary(s.key.span, "this pass has no depth buffer")
                    .with_help("only `render(...)` and `lines(...)` passes draw geometry with a depth test"),
            );
            return;
        };
        match &s.value.kind {
            AK::Name(n) if n.name == "keep" && is_lines => self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "a lines pass has no depth of its own to keep")
                    .with_primary(s.value.span, "`keep` on a lines pass")
                    .with_help("lines test against a render pass's depth: `depth: test(shade, bias: 1px)`; keep the depth in that render pass"),
            ),
            AK::Name(n) if n.name == "keep" => *depth = PassDepth::Keep,
            AK::Call(c) if c.callee.name == "test" => {
                // The setting's own span runs on over trailing whitespace.
                if let Some(test) = self.depth_test(c, s.key.span.to(s.value.span)) {
                    *depth = test;
                }
            }
            other => {
                let written = match other {
                    AK::Name(n) => n.name.as_str(),
                    AK::Call(c) => c.callee.name.as_str(),
                    _ => "",
                };
                let mut d = Diagnostic::error(codes::BAD_ARGUMENT, "unknown depth mode")
                    .with_primary(s.value.span, "not a depth mode");
                d = match did_you_mean(written, ["keep", "test"]) {
                    Some("keep") => d.with_help("did you mean `keep`?"),
                    Some(_) => d.with_help("did you mean `test(pass)`?"),
                    None => d.with_help(
                        "write `depth: keep` (later passes test against this pass's depth) or \
                         `depth: test(pass, bias: 1px)`",
                    ),
                };
                self.error(d);
            }
        }
    }

    /// `schedule: naive | auto | tiled` of an image pass: the schedule the
    /// style asks of it. Only image passes are fused or tiled, so on any
    /// other kind the setting would mean nothing and is refused rather
    /// than ignored.
    pub(super) fn schedule_setting(&mut self, kind: &mut PassKind, s: &ast::Setting, seen: &mut Option<Span>) {
        let span = s.key.span.to(s.value.span);
        if let Some(first) = *seen {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "`schedule` is set twice")
                    .with_primary(span, "second `schedule`")
                    .with_secondary(first, "first `schedule`")
                    .with_help("a pass runs under one schedule"),
            );
            return;
        }
        *seen = Some(span);
        let PassKind::Image { schedule, .. } = kind else {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "`schedule` is a setting of image passes")
                    .with_primary(s.key.span, format!("this is a {} pass", kind.name()))
                    .with_help("only image passes are fused or tiled; every other pass runs as written"),
            );
            return;
        };
        let name = match &s.value.kind {
            AK::Name(n) => n.name.as_str(),
            _ => "",
        };
        let Some(mode) = Schedule::parse(name) else {
            let names = Schedule::ALL.map(Schedule::name);
            let mut d = Diagnostic::error(
                codes::BAD_ARGUMENT,
                if name.is_empty() {
                    "`schedule` takes a schedule's name".to_string()
                } else {
                    format!("unknown schedule `{name}`")
                },
            )
            .with_primary(s.value.span, "not a schedule");
            d = match did_you_mean(name, names) {
                Some(m) => d.with_help(format!("did you mean `{m}`?")),
                None => d.with_help(
                    "write `schedule: naive` (run as written), `schedule: tiled` (compute over tiles) \
                     or `schedule: auto` (the compiler decides)",
                ),
            };
            self.error(d);
            return;
        };
        *schedule = Some(PassSchedule { schedule: mode, span });
    }

    /// E0319: `depth: test(name)` where `name` is declared, but neither a
    /// pass nor an `input(depth)` texture.
    fn not_a_tested_depth(&self, name: &str, at: Span, symbol: Symbol, declared: Span) -> Diagnostic {
        let what = match symbol {
            Symbol::Texture(tid) => match &self.ir.textures[tid.0 as usize].source {
                TextureSource::Input(kind) => format!("an `input({})` texture", kind.name()),
                _ => "a texture".to_string(),
            },
            Symbol::Param(_) | Symbol::Gradient(_) => "a parameter".to_string(),
            Symbol::Pass(_) => "a pass".to_string(),
        };
        let depth_inputs: Vec<&str> = self
            .ir
            .textures
            .iter()
            .filter(|t| t.source == TextureSource::Input(InputKind::Depth))
            .map(|t| t.name.as_str())
            .collect();
        let help = match depth_inputs.as_slice() {
            [] => "a depth test names an earlier pass with `depth: keep`, or the host's depth: declare \
                   `texture depth = input(depth)` and write `depth: test(depth)`"
                .to_string(),
            names => format!(
                "a depth test names an earlier pass with `depth: keep`, or an `input(depth)` texture: {}",
                names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
            ),
        };
        Diagnostic::error(
            codes::NOT_A_TESTED_DEPTH,
            format!("`{name}` is {what}, not a depth to test against"),
        )
        .with_primary(at, "neither a pass nor a depth input")
        .with_secondary(declared, format!("`{name}` is declared here as {what}"))
        .with_help(help)
    }

    /// `test(pass, bias: b)`: the tested pass or depth input, and the bias,
    /// a literal in px (slope-scaled) or without unit (window depth).
    fn depth_test(&mut self, c: &ast::Call, span: Span) -> Option<PassDepth> {
        let mut pass = None;
        let (mut bias_px, mut bias_depth) = (0.0, 0.0);
        let usage = "write `depth: test(gbuffer)`, `test(gbuffer, bias: 2px)` or `test(gbuffer, bias: 0.001)`";
        for a in &c.args {
            match (&a.name, &a.value.kind) {
                (None, AK::Name(n)) if pass.is_none() => match self.names.get(&n.name).copied() {
                    Some((Symbol::Pass(pid), _)) => pass = Some(TestedDepth::Pass(pid)),
                    Some((Symbol::Texture(tid), _))
                        if self.ir.textures[tid.0 as usize].source == TextureSource::Input(InputKind::Depth) =>
                    {
                        pass = Some(TestedDepth::Input(tid));
                    }
                    Some((symbol, declared)) => {
                        self.error(self.not_a_tested_depth(&n.name, n.span, symbol, declared));
                        return None;
                    }
                    None => {
                        let passes: Vec<String> = self.ir.passes.iter().map(|p| p.name.clone()).collect();
                        let mut d = Diagnostic::error(codes::UNKNOWN_NAME, format!("no pass named `{}`", n.name))
                            .with_primary(n.span, "not a pass");
                        if let Some(s) = did_you_mean(&n.name, passes.iter().map(String::as_str)) {
                            d = d.with_help(format!("did you mean `{s}`?"));
                        }
                        self.error(d);
                        return None;
                    }
                },
                (Some(k), value) if k.name == "bias" => {
                    let AK::Number { value, unit, .. } = value else {
                        self.error(
                            Diagnostic::error(codes::BAD_ARGUMENT, "a depth bias is a number")
                                .with_primary(a.value.span, "not a number literal")
                                .with_help("write `bias: 2px` (slope-scaled) or `bias: 0.001` (window depth)"),
                        );
                        return None;
                    };
                    match unit {
                        Some(UnitSuffix::Px) if *value <= npr_abi::validate::MAX_DEPTH_BIAS_PX => bias_px = *value,
                        None if *value < 1.0 => bias_depth = *value,
                        Some(UnitSuffix::Px) | None => {
                            let range = if unit.is_some() {
                                format!("0px..{}px", npr_abi::validate::MAX_DEPTH_BIAS_PX)
                            } else {
                                "[0, 1) of the depth range".to_string()
                            };
                            self.error(
                                Diagnostic::error(codes::OUT_OF_RANGE, "depth bias out of range")
                                    .with_primary(a.value.span, format!("outside {range}")),
                            );
                            return None;
                        }
                        Some(u) => {
                            self.error(
                                Diagnostic::error(codes::UNIT_MISMATCH, format!("a depth bias in `{}`", u.as_str()))
                                    .with_primary(a.value.span, "neither px nor depth units")
                                    .with_help("write `bias: 2px` (slope-scaled) or `bias: 0.001` (window depth)"),
                            );
                            return None;
                        }
                    }
                }
                _ => {
                    self.error(
                        Diagnostic::error(codes::BAD_ARGUMENT, "unexpected argument to `test`")
                            .with_primary(a.span, "not understood")
                            .with_help(usage),
                    );
                    return None;
                }
            }
        }
        let Some(pass) = pass else {
            self.error(
                Diagnostic::error(
                    codes::BAD_ARGUMENT,
                    "`test` needs the pass whose depth it tests against",
                )
                .with_primary(c.span, "no pass given")
                .with_help(usage),
            );
            return None;
        };
        Some(PassDepth::Test {
            against: pass,
            bias_px,
            bias_depth,
            span,
        })
    }
}
