//! The arguments of a pass kind (`render(tag)`, `image(a, b)`,
//! `compute(pixels, ids.id)`): only `compute(pixels, ...)` takes a pass's
//! target; everywhere else an argument is a plain name.

use super::Resolver;
use dsl::{ast, codes, Diagnostic};

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
}
