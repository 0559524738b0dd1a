//! Resolve `texture name = input(kind, ...)`: an image the host gives
//! (issue 47), with the semantic kind that fixes its convention inside the
//! language (`npr_abi::input`). The kind's one qualifier is said once, in
//! the declaration: `input(color, linear|display)`, `input(depth)`,
//! `input(normal, world|view)`, `input(id)`, `input(motion)`,
//! `input(image, FORMAT)`.

use super::Resolver;
use npr_abi::{Format, InputKind, NormalSpace};
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic};
use npr_dsl::ast::{self, ExprKind as AK};

/// How each kind is written, for help texts.
const FORMS: &str =
    "`input(color, linear)`, `input(color, display)`, `input(depth)`, `input(normal, world)`, `input(normal, view)`, `input(id)`, `input(motion)` or `input(image, rgba16float)`";

impl Resolver<'_> {
    /// The kind of an `input(...)` call; `None` after an error.
    pub(super) fn input_kind(&mut self, call: &ast::Call) -> Option<InputKind> {
        let mut words = Vec::new();
        for a in &call.args {
            match (&a.name, &a.value.kind) {
                (None, AK::Name(n)) => words.push((n.name.as_str(), a.value.span)),
                _ => {
                    self.error(
                        Diagnostic::error(codes::BAD_ARGUMENT, "unexpected argument to `input`")
                            .with_primary(a.span, "not an input kind or its qualifier")
                            .with_help(format!("write one of {FORMS}")),
                    );
                    return None;
                }
            }
        }
        let Some(&(kind, kind_span)) = words.first() else {
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, "`input` needs the kind of image the host gives")
                    .with_primary(call.span, "no kind given")
                    .with_help(format!("write one of {FORMS}")),
            );
            return None;
        };
        // The qualifier each kind takes: its allowed words, and what it means.
        let qualifiers: &[&str] = match kind {
            "color" => &["linear", "display"],
            "normal" => &["world", "view"],
            "image" => &[],
            "depth" | "id" | "motion" => &[],
            other => {
                let mut d = Diagnostic::error(codes::BAD_ARGUMENT, format!("unknown input kind `{other}`"))
                    .with_primary(kind_span, "not an input kind");
                d = match did_you_mean(other, InputKind::NAMES) {
                    Some(s) => d.with_help(format!("did you mean `{s}`?")),
                    None => d.with_help(format!("the kinds are: {}", InputKind::NAMES.join(", "))),
                };
                self.error(d);
                return None;
            }
        };
        let takes_one = matches!(kind, "color" | "normal" | "image");
        if words.len() > 1 + takes_one as usize {
            let (_, extra) = words[1 + takes_one as usize];
            self.error(
                Diagnostic::error(
                    codes::BAD_ARGUMENT,
                    format!("too many arguments to `input({kind}, ...)`"),
                )
                .with_primary(extra, "not expected here")
                .with_help(format!("write one of {FORMS}")),
            );
            return None;
        }
        if takes_one && words.len() < 2 {
            let what = match kind {
                "color" => "whether the host's colour is `linear` light or `display`-referred (sRGB)",
                "normal" => "the space the style reads the normal in: `world` or `view`",
                _ => "the format the image is read as, e.g. `rgba16float`",
            };
            self.error(
                Diagnostic::error(codes::BAD_ARGUMENT, format!("`input({kind})` needs {what}"))
                    .with_primary(call.span, "said nowhere")
                    .with_help(format!("write one of {FORMS}")),
            );
            return None;
        }
        let qualifier = words.get(1).copied();
        if kind == "image" {
            let (name, span) = qualifier?;
            return match Format::parse(name) {
                Some(format) => Some(InputKind::Image { format }),
                None => {
                    let mut d = Diagnostic::error(codes::BAD_ARGUMENT, format!("unknown format `{name}`"))
                        .with_primary(span, "not a texture format");
                    let names = Format::ALL.iter().map(|(n, _)| *n);
                    d = match did_you_mean(name, names.clone()) {
                        Some(s) => d.with_help(format!("did you mean `{s}`?")),
                        None => d.with_help(format!("the formats are: {}", names.collect::<Vec<_>>().join(", "))),
                    };
                    self.error(d);
                    None
                }
            };
        }
        if let Some((word, span)) = qualifier {
            if !qualifiers.contains(&word) {
                let mut d = Diagnostic::error(
                    codes::BAD_ARGUMENT,
                    format!("`input({kind}, ...)` takes `{}`", qualifiers.join("` or `")),
                )
                .with_primary(span, format!("`{word}` is not one of them"));
                if let Some(s) = did_you_mean(word, qualifiers.iter().copied()) {
                    d = d.with_help(format!("did you mean `{s}`?"));
                }
                self.error(d);
                return None;
            }
        }
        Some(match (kind, qualifier.map(|q| q.0)) {
            ("color", Some(q)) => InputKind::Color {
                display: q == "display",
            },
            ("normal", Some("view")) => InputKind::Normal {
                space: NormalSpace::View,
            },
            ("normal", _) => InputKind::Normal {
                space: NormalSpace::World,
            },
            ("depth", _) => InputKind::Depth,
            ("id", _) => InputKind::Id,
            _ => InputKind::Motion,
        })
    }
}
