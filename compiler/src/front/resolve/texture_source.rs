//! Resolve a `texture name = source(...) { options }` declaration (and the
//! default of an `object param t: texture`): which source it names
//! (`image`, `noise` or `halftone_table`), that source's arguments, and the
//! sampler options.

use super::{Resolver, MAX_NOISE_SIZE};
use crate::front::param_values::suffix_of;
use crate::ir::*;
use crate::ir::{Literal, ParamSetting, SettingOrigin};
use npr_abi::{HalftoneTableSpec, NoiseSpec};
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic, Span};
use npr_dsl::ast::{self, ExprKind as AK};
use std::path::Path;

/// The texture sources a declaration may name.
const SOURCES: [&str; 7] = [
    "image",
    "noise",
    "halftone_table",
    "artmap",
    "ripmap",
    "filter_input",
    "input",
];

impl Resolver<'_> {
    /// The arguments of `image("path.png", srgb|linear)`: the path as
    /// written, resolved against `dir`, and the colour space; `None` after
    /// an error.
    fn image_args(&mut self, call: &ast::Call, dir: &Path) -> Option<(String, String, bool)> {
        let mut path = None;
        let mut srgb = true;
        for a in &call.args {
            match (&a.name, &a.value.kind) {
                (None, AK::Str(s)) => path = Some((s.clone(), a.value.span)),
                (None, AK::Name(n)) if n.name == "srgb" => srgb = true,
                (None, AK::Name(n)) if n.name == "linear" => srgb = false,
                _ => self.error(
                    Diagnostic::error(codes::BAD_ARGUMENT, "unexpected argument to `image`")
                        .with_primary(a.span, "not understood")
                        .with_help("write `image(\"path.png\", srgb)` or `image(\"path.png\", linear)`"),
                ),
            }
        }
        let Some((p, span)) = path else {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "`image` needs a file path")
                    .with_primary(call.span, "no path given")
                    .with_help("write `image(\"textures/paper.png\", srgb)`"),
            );
            return None;
        };
        let resolved = dir.join(&p);
        if let Some(refused) = crate::front::paths::check(self.paths, span, &p, &resolved) {
            self.error(refused);
            return None;
        }
        if !self.files.is_file(&resolved) {
            self.error(
                Diagnostic::error(codes::MISSING_TEXTURE, format!("texture file `{p}` not found"))
                    .with_primary(span, format!("looked for {}", resolved.display()))
                    .with_help(
                        "paths are relative to the .npr file; generate a texture with `noise(...)` if you have none",
                    ),
            );
        }
        Some((p, resolved.display().to_string(), srgb))
    }

    /// `artmap(image("…"), filter: "filter.npr", levels: auto|N)`
    /// (Klein et al. 2000 §4.2); the filter itself was loaded by
    /// `load_filters` under the path it resolves to.
    fn artmap(&mut self, t: &ast::TextureDecl, dir: &Path, rip: bool) -> Option<TextureSource> {
        let mut image = None;
        let mut filter = None;
        let mut levels = None;
        for a in &t.source.args {
            match (a.name.as_ref().map(|n| n.name.as_str()), &a.value.kind) {
                (None, AK::Call(c)) if c.callee.name == "image" && image.is_none() => {
                    image = self.image_args(c, dir);
                    image.as_ref()?;
                }
                (Some("filter"), AK::Str(rel)) => {
                    let file = dir.join(rel).display().to_string();
                    filter = Some((rel.clone(), file.clone(), file, Vec::new()))
                }
                (Some("filter"), AK::Call(c)) if c.callee.name == "filter" => filter = self.filter_call(c, dir),
                (Some("filter"), _) => self.error(
                    Diagnostic::error(
                        codes::BAD_ARGUMENT,
                        "an art-map's `filter` is the path of a filter style",
                    )
                    .with_primary(a.value.span, "not a path")
                    .with_help(
                        "write `filter: \"filters/hatching.npr\"`, relative to this file, or with new values for its params: `filter: filter(\"filters/hatching.npr\", spacing: 8)`",
                    ),
                ),
                (Some("levels"), AK::Name(n)) if n.name == "auto" => levels = None,
                (Some("levels"), _) => {
                    let id = self.expr(&a.value);
                    let max = npr_abi::ArtmapSpec::MAX_LEVELS;
                    match self.const_scalar(id, "an art-map's levels") {
                        Some(v) if v.fract() == 0.0 && (1.0..=max as f64).contains(&v) => levels = Some(v as u32),
                        Some(v) => self.error(
                            Diagnostic::error(
                                codes::OUT_OF_RANGE,
                                format!("an art-map's `levels` is `auto` or a whole number in 1..{max}"),
                            )
                            .with_primary(a.value.span, format!("{v} is not allowed")),
                        ),
                        None => {}
                    }
                }
                (name, _) => {
                    let known = ["filter", "levels"];
                    let mut d = Diagnostic::error(codes::BAD_ARGUMENT, "unexpected argument to `artmap`")
                        .with_primary(a.span, "not an art-map setting");
                    d = match name.and_then(|n| did_you_mean(n, known)) {
                        Some(s) => d.with_help(format!("did you mean `{s}`?")),
                        None => d.with_help(
                            "write `artmap(image(\"brick.png\", srgb), filter: \"filters/hatching.npr\", levels: auto)`",
                        ),
                    };
                    self.error(d);
                }
            }
        }
        let Some((path, resolved, srgb)) = image else {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "an art-map needs a source image")
                    .with_primary(t.source.span, "no `image(\"…\")` first")
                    .with_help("write `artmap(image(\"brick.png\", srgb), filter: \"filters/hatching.npr\")`"),
            );
            return None;
        };
        let Some((filter_name, filter, filter_file, filter_args)) = filter else {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "an art-map needs a `filter`")
                    .with_primary(t.source.span, "no filter named")
                    .with_help(
                        "add `filter: \"filters/hatching.npr\"`: the style whose image passes filter each level",
                    ),
            );
            return None;
        };
        if rip && levels.is_some() {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "a rip-map has all its levels")
                    .with_primary(t.source.span, "`levels` is for `artmap`")
                    .with_help("remove `levels`: `sample_ripmap` may read any level of either axis"),
            );
        }
        Some(TextureSource::Artmap {
            path,
            resolved,
            srgb,
            filter,
            filter_file,
            filter_name,
            filter_args,
            levels,
            rip,
        })
    }

    /// `filter("path", name: value, ...)`: the path as written, the
    /// compiled filter's key (the resolved path, and the arguments when
    /// there are any: one compiled filter per argument list), the resolved
    /// path (`load_filters`' key) and the arguments as settings. Whether
    /// the filter has such params, of that type, unit and range, is checked
    /// when it is compiled (`param_settings`, as for `--set`).
    fn filter_call(&mut self, c: &ast::Call, dir: &Path) -> Option<(String, String, String, Vec<ParamSetting>)> {
        let usage =
            "write `filter(\"filters/hatching.npr\", spacing: 8)`: the filter's path, then new values for its params";
        let rel = match c.args.first().map(|a| (&a.name, &a.value.kind)) {
            Some((None, AK::Str(rel))) => rel.clone(),
            _ => {
                self.error(
                    Diagnostic::error(codes::BAD_ARGUMENT, "`filter(...)` starts with the filter's path")
                        .with_primary(c.span, "no path first")
                        .with_help(usage),
                );
                return None;
            }
        };
        let mut args: Vec<(ParamSetting, Span)> = Vec::new();
        for a in c.args.iter().skip(1) {
            let Some(name) = &a.name else {
                self.error(
                    Diagnostic::error(codes::BAD_ARGUMENT, "a filter's argument needs the param's name")
                        .with_primary(a.span, "no name")
                        .with_help(usage),
                );
                continue;
            };
            if let Some((_, first)) = args.iter().find(|(x, _)| x.name == name.name) {
                self.error(
                    Diagnostic::error(codes::DUPLICATE_NAME, format!("`{}` is given twice", name.name))
                        .with_primary(a.span, "given again here")
                        .with_secondary(*first, "first here"),
                );
                continue;
            }
            let Some(value) = self.filter_arg_value(&a.value) else {
                continue;
            };
            let setting = ParamSetting {
                name: name.name.clone(),
                name_span: name.span,
                value,
                value_span: a.value.span,
                origin: SettingOrigin::FilterArgument { filter: rel.clone() },
            };
            args.push((setting, a.span));
        }
        let args: Vec<ParamSetting> = args.into_iter().map(|(s, _)| s).collect();
        let resolved = dir.join(&rel).display().to_string();
        let key = if args.is_empty() {
            resolved.clone()
        } else {
            let list: Vec<String> = args.iter().map(|a| format!("{}={:?}", a.name, a.value)).collect();
            format!("{resolved}?{}", list.join("&"))
        };
        Some((rel, key, resolved, args))
    }

    /// A filter's argument as a literal: a bare name the host does not bind
    /// is the choice of one of the filter's enum params (`mode: soft`), as
    /// `--set mode=soft` is (the host's own variants and names are not the
    /// filter's); anything else a constant, read as it was written (a
    /// colour, a range, whole numbers or not, with its unit).
    fn filter_arg_value(&mut self, value: &ast::Expr) -> Option<Literal> {
        match &value.kind {
            AK::Name(choice) if !self.is_bound(&choice.name) => return Some(Literal::Name(choice.name.clone())),
            AK::Color(c) => return Some(Literal::Colour(*c)),
            _ => {}
        }
        let id = self.expr(value);
        let unit = self.ir.expr(id).unit;
        let constant = self.constant(id)?;
        Some(match (&value.kind, constant) {
            (AK::Range { .. }, Const::Vec(v)) if v.len() == 2 => Literal::Range(v[0], v[1]),
            (_, Const::Bool(b)) => Literal::Bool(b),
            (_, c) => Literal::Numbers {
                whole: matches!(c, Const::Int(_)),
                values: c.as_f64s(),
                suffix: suffix_of(unit).to_string(),
            },
        })
    }

    /// `halftone_table(edge: 0.1, correction: on)`: the tone-correction table
    /// of `halftone(...)` (Breslav et al. 2007 §3.5), built by the runner.
    fn halftone_table(&mut self, t: &ast::TextureDecl) -> HalftoneTableSpec {
        let mut spec = HalftoneTableSpec {
            edge: 0.1,
            corrected: true,
        };
        let (lo, hi) = HalftoneTableSpec::EDGE_RANGE;
        for a in &t.source.args {
            match a.name.as_ref().map(|n| n.name.as_str()) {
                Some("edge") => {
                    let id = self.expr(&a.value);
                    let Some(v) = self.const_scalar(id, "a halftone table's edge") else {
                        continue;
                    };
                    if HalftoneTableSpec::edge_ok(v) {
                        spec.edge = v as f32;
                    } else {
                        self.error(
                            Diagnostic::error(codes::OUT_OF_RANGE, format!("a halftone table's `edge` must be in {lo}..{hi}"))
                                .with_primary(a.value.span, format!("{v} is not allowed"))
                                .with_help("the edge is the half-width of the dots' soft edge, in screen heights: e.g. `edge: 0.1`"),
                        );
                    }
                }
                Some("correction") => match &a.value.kind {
                    AK::Name(n) if n.name == "on" => spec.corrected = true,
                    AK::Name(n) if n.name == "off" => spec.corrected = false,
                    AK::Bool(b) => spec.corrected = *b,
                    _ => self.error(
                        Diagnostic::error(codes::BAD_ARGUMENT, "halftone table `correction` must be `on` or `off`")
                            .with_primary(a.value.span, "not understood")
                            .with_help("write `correction: on` (the default) or `correction: off`"),
                    ),
                },
                name => {
                    let known = ["edge", "correction"];
                    let mut d = Diagnostic::error(codes::BAD_ARGUMENT, "unexpected argument to `halftone_table`")
                        .with_primary(a.span, "not a halftone table setting");
                    d = match name.and_then(|n| did_you_mean(n, known)) {
                        Some(s) => d.with_help(format!("did you mean `{s}`?")),
                        None => d.with_help(format!(
                            "write `halftone_table(edge: 0.1, correction: on)`; its settings are: {}",
                            known.join(", ")
                        )),
                    };
                    self.error(d);
                }
            }
        }
        spec
    }

    pub(super) fn texture(&mut self, t: &ast::TextureDecl, dir: &Path) -> Texture {
        let mut tex = Texture {
            name: t.name.name.clone(),
            doc: t.doc.clone(),
            source: TextureSource::Noise(NoiseSpec {
                size: 1,
                octaves: 1,
                seed: 0,
                gradient: false,
                channels: 1,
                frequency: 4,
            }),
            wrap_repeat: true,
            filter_linear: true,
            mips: false,
            per_object: false,
            span: t.span,
        };
        let callee = t.source.callee.name.as_str();
        match callee {
            "image" => {
                if let Some((path, resolved, srgb)) = self.image_args(&t.source, dir) {
                    tex.source = TextureSource::Image { path, resolved, srgb };
                }
            }
            "artmap" => {
                if let Some(source) = self.artmap(t, dir, false) {
                    tex.source = source;
                    // A mip chain, sampled trilinearly: the hardware's level
                    // blend is what blends the strokes of neighbouring levels.
                    tex.mips = true;
                    tex.filter_linear = true;
                }
            }
            "ripmap" => {
                if let Some(source) = self.artmap(t, dir, true) {
                    tex.source = source;
                    // One atlas level, read bilinearly inside each level's
                    // rectangle by `sample_ripmap` (which wraps uv itself).
                    tex.mips = false;
                    tex.filter_linear = true;
                    tex.wrap_repeat = false;
                }
            }
            "input" => {
                if let Some(kind) = self.input_kind(&t.source) {
                    tex.source = TextureSource::Input(kind);
                }
                // Read texel by texel at the host's size, clamped at its
                // edges: a depth or id must not be blended between texels.
                tex.wrap_repeat = false;
                tex.filter_linear = false;
                tex.mips = false;
            }
            "filter_input" => {
                if !t.source.args.is_empty() {
                    self.error(
                        Diagnostic::error(codes::BAD_ARGUMENT, "`filter_input()` takes no arguments")
                            .with_primary(t.source.span, "the level comes from the art-map"),
                    );
                }
                tex.source = TextureSource::FilterInput;
                // Read texel by texel at the level's own size, clamped at its edges.
                tex.wrap_repeat = false;
                tex.mips = false;
            }
            "noise" => {
                let get = |name: &str, default: f64, lo: f64, hi: f64, this: &mut Self| -> f64 {
                    let Some(a) = t
                        .source
                        .args
                        .iter()
                        .find(|a| a.name.as_ref().is_some_and(|n| n.name == name))
                    else {
                        return default;
                    };
                    let id = this.expr(&a.value);
                    let Some(v) = this.const_scalar(id, "a noise setting") else {
                        return default;
                    };
                    if v < lo || v > hi || v.fract() != 0.0 {
                        let code = if name == "size" && v > hi {
                            codes::LIMIT_EXCEEDED
                        } else {
                            codes::OUT_OF_RANGE
                        };
                        this.error(
                            Diagnostic::error(code, format!("noise `{name}` must be a whole number in {lo}..{hi}"))
                                .with_primary(a.value.span, format!("{v} is not allowed")),
                        );
                        return default;
                    }
                    v
                };
                for a in &t.source.args {
                    let known = ["size", "octaves", "seed", "kind", "channels", "frequency"];
                    match &a.name {
                        Some(n) if known.contains(&n.name.as_str()) => {}
                        _ => {
                            let mut d = Diagnostic::error(codes::BAD_ARGUMENT, "unexpected argument to `noise`")
                                .with_primary(a.span, "not a noise setting");
                            if let Some(s) = a.name.as_ref().and_then(|n| did_you_mean(&n.name, known)) {
                                d = d.with_help(format!("did you mean `{s}`?"));
                            } else {
                                d = d.with_help(format!("noise settings are: {}", known.join(", ")));
                            }
                            self.error(d);
                        }
                    }
                }
                let size = get("size", 256.0, 1.0, MAX_NOISE_SIZE as f64, self) as u32;
                let octaves = get("octaves", 4.0, 1.0, 12.0, self) as u32;
                let seed = get("seed", 0.0, 0.0, u32::MAX as f64, self) as u32;
                let channels = get("channels", 1.0, 1.0, 4.0, self) as u32;
                let frequency = get("frequency", 4.0, 1.0, 256.0, self) as u32;
                let mut gradient = false;
                if let Some(a) = t
                    .source
                    .args
                    .iter()
                    .find(|a| a.name.as_ref().is_some_and(|n| n.name == "kind"))
                {
                    match &a.value.kind {
                        AK::Name(n) if n.name == "value" => gradient = false,
                        AK::Name(n) if n.name == "gradient" => gradient = true,
                        _ => self.error(
                            Diagnostic::error(codes::BAD_ARGUMENT, "noise `kind` must be `value` or `gradient`")
                                .with_primary(a.value.span, "unknown kind"),
                        ),
                    }
                }
                tex.source = TextureSource::Noise(NoiseSpec {
                    size,
                    octaves,
                    seed,
                    gradient,
                    channels,
                    frequency,
                });
                tex.wrap_repeat = true;
            }
            "halftone_table" => {
                tex.source = TextureSource::HalftoneTable(self.halftone_table(t));
                // Read texel by texel (`npr_halftone`): no filtering, no wrap.
                tex.wrap_repeat = false;
                tex.filter_linear = false;
            }
            other => {
                let mut d = Diagnostic::error(codes::UNKNOWN_OPERATOR, format!("unknown texture source `{other}`"))
                    .with_primary(t.source.callee.span, "not a texture source");
                d = match did_you_mean(other, SOURCES) {
                    Some(s) => d.with_help(format!("did you mean `{s}`?")),
                    None => d.with_help(
                        "textures come from `image(\"file.png\")`, `noise(size: 256, octaves: 4)`, `halftone_table(edge: 0.1)`, `artmap(image(\"file.png\"), filter: \"filter.npr\")` or the host: `input(color, linear)`",
                    ),
                };
                self.error(d);
            }
        }
        for s in &t.options {
            let value = match &s.value.kind {
                AK::Name(n) => n.name.as_str(),
                AK::Bool(true) => "on",
                AK::Bool(false) => "off",
                _ => "",
            };
            match (s.key.name.as_str(), value) {
                ("wrap", "repeat") => tex.wrap_repeat = true,
                ("wrap", "clamp") => tex.wrap_repeat = false,
                ("filter", "linear") => tex.filter_linear = true,
                ("filter", "nearest") => tex.filter_linear = false,
                ("mips", "on") => tex.mips = true,
                ("mips", "off") => tex.mips = false,
                (key, _) => {
                    let help = match key {
                        "wrap" => "`wrap` is `repeat` or `clamp`",
                        "filter" => "`filter` is `linear` or `nearest`",
                        "mips" => "`mips` is `on` or `off`",
                        _ => "texture options are `wrap`, `filter` and `mips`",
                    };
                    self.error(
                        Diagnostic::error(codes::BAD_ARGUMENT, format!("bad texture option `{key}`"))
                            .with_primary(s.span, "not understood")
                            .with_help(help),
                    );
                }
            }
        }
        if matches!(tex.source, TextureSource::Artmap { rip: false, .. }) && !tex.mips {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "an art-map cannot have `mips: off`")
                    .with_primary(t.span, "an art-map is its filtered mip chain")
                    .with_help("remove `mips: off`; use `image(...)` for a texture without mips"),
            );
        }
        if matches!(tex.source, TextureSource::Artmap { rip: true, .. }) {
            if let Some(s) = t
                .options
                .iter()
                .find(|s| ["wrap", "mips"].contains(&s.key.name.as_str()))
            {
                self.error(
                    Diagnostic::error(codes::BAD_ARGUMENT, format!("a rip-map has no `{}` option", s.key.name))
                        .with_primary(s.span, "a rip-map is one atlas, read by `sample_ripmap`")
                        .with_help("`sample_ripmap` selects the level of each axis itself and always repeats"),
                );
            }
            // The atlas's own sampler: clamped (levels sit side by side).
            tex.wrap_repeat = false;
            tex.mips = false;
        }
        if matches!(tex.source, TextureSource::Input(_)) {
            if let Some(s) = t.options.iter().find(|s| s.key.name == "mips") {
                self.error(
                    Diagnostic::error(codes::BAD_ARGUMENT, "a host input has no `mips` option")
                        .with_primary(s.span, "the host gives one image per frame, with no mip chain")
                        .with_help("remove `mips`; blur it in an image pass if the style needs a smaller copy"),
                );
            }
            tex.mips = false;
        }
        tex
    }
}
