//! The arguments of a pass kind (`render(tag)`, `image(a, b)`,
//! `compute(pixels, ids.id)`): only `compute(pixels, ...)` takes a pass's
//! target; everywhere else an argument is a plain name.

use super::Resolver;
use npr_diag::{codes, Diagnostic};
use npr_dsl::ast;

impl Resolver<'_> {
    /// The kind's arguments as names; an argument written as a target
    /// (`a.b`) is reported, since `what` is expected there.
    pub(super) fn plain_kind_args<'p>(&mut self, p: &'p ast::PassDecl, what: &str) -> Vec<&'p ast::Ident> {
        for a in &p.kind.args {
            self.no_field(a, what);
        }
        p.kind.args.iter().map(|a| &a.name).collect()
    }

    /// Report `a.b` where `what` (a plain name) is expected.
    pub(super) fn no_field(&mut self, a: &ast::KindArg, what: &str) {
        if let Some(field) = &a.field {
            self.error(
                Diagnostic::error(
                    codes::BAD_PASS_INPUT,
                    format!("expected {what}, found the target `{}.{}`", a.name.name, field.name),
                )
                .with_primary(a.span, format!("{what} is a plain name here"))
                .with_help(format!(
                    "write `{}`; only `compute(pixels, pass.target)` names a target in a pass kind",
                    a.name.name
                )),
            );
        }
    }

    /// `kind(scene)` (every object: `None`) or `kind(tag)`; a second
    /// argument is E0304 with `what` as its message.
    pub(super) fn scene_or_tag(&mut self, p: &ast::PassDecl, what: &str) -> Option<String> {
        let kind = p.kind.kind.name.clone();
        let args = self.plain_kind_args(p, "a tag");
        match args.as_slice() {
            [] => None,
            [a] if a.name == "scene" => None,
            [a] => Some(a.name.clone()),
            [_, extra, ..] => {
                let extra = extra.span;
                self.error(
                    Diagnostic::error(codes::BAD_PASS_INPUT, what)
                        .with_primary(extra, "unexpected")
                        .with_help(format!(
                            "write `{kind}(scene)` for all objects or `{kind}(tag)` for tagged ones"
                        )),
                );
                None
            }
        }
    }
}
