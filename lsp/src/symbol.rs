//! What a token under the cursor names: a `let` of its pass, a param, a
//! texture, a pass, one of a pass's targets, a builtin, a stdlib operator,
//! an intrinsic, an operator's parameter, a pass kind or a format. Lets
//! shadow params as in resolve.

use super::analysis::{self, Analysis};
use super::tokens::Token;
use npr_compiler::ir::{Builtin, Intrinsic};
use npr_dsl::ast::{LetBinding, ParamDecl, PassDecl, TextureDecl};

pub enum Symbol<'a> {
    Let(&'a LetBinding),
    Param(&'a ParamDecl),
    Texture(&'a TextureDecl),
    Pass(&'a PassDecl),
    Target(&'a PassDecl, analysis::Target<'a>),
    Builtin(&'static str, Builtin),
    Operator(&'static npr_stdlib::Operator),
    Intrinsic(&'static str, Intrinsic),
    /// A call the compiler treats specially (`previous`, `noise`...): as written, what it does.
    Special(&'static str, &'static str),
    OperatorParam(&'static npr_stdlib::Operator, &'static npr_stdlib::Param),
    PassKind(String),
    Format(&'static str, npr_abi::Format),
}

pub fn resolve<'a>(a: &'a Analysis, token: &Token<'a>, pass: Option<&'a PassDecl>) -> Option<Symbol<'a>> {
    match token {
        Token::Name { ident, member } => name(a, &ident.name, *member, pass),
        Token::Declared(ident) => name(a, &ident.name, None, pass).or_else(|| {
            // An output, state or reduction name: the pass's own target.
            let p = pass?;
            let t = analysis::targets(p).into_iter().find(|t| t.name == ident.name)?;
            Some(Symbol::Target(p, t))
        }),
        Token::Field { base, field } => {
            if let Some(p) = a.pass(&base.name) {
                let t = analysis::targets(p).into_iter().find(|t| t.name == field.name)?;
                return Some(Symbol::Target(p, t));
            }
            let spelling = format!("{}.{}", base.name, field.name);
            builtin(&spelling)
        }
        Token::Callee(call) => callee(&call.callee.name),
        Token::ArgName { call, name } => {
            let op = npr_stdlib::find(&call.callee.name)?;
            op.params
                .iter()
                .find(|p| p.name == name.name)
                .map(|p| Symbol::OperatorParam(op, p))
        }
        Token::Format(f) => npr_abi::Format::ALL
            .iter()
            .find(|(n, _)| *n == f.name)
            .map(|(n, fmt)| Symbol::Format(n, *fmt)),
        Token::PassKind(k) => Some(Symbol::PassKind(k.name.clone())),
    }
}

/// A bare name: a let of the pass, a param, a texture, a pass, then a
/// builtin (with its member: `light` of `light.dir`).
fn name<'a>(
    a: &'a Analysis,
    name: &str,
    member: Option<&npr_dsl::ast::Ident>,
    pass: Option<&'a PassDecl>,
) -> Option<Symbol<'a>> {
    if let Some(l) = pass.and_then(|p| p.body.lets.iter().find(|l| l.name.name == name)) {
        return Some(Symbol::Let(l));
    }
    if let Some(p) = a.param(name) {
        return Some(Symbol::Param(p));
    }
    if let Some(t) = a.texture(name) {
        return Some(Symbol::Texture(t));
    }
    if let Some(p) = a.pass(name) {
        return Some(Symbol::Pass(p));
    }
    if let Some(m) = member {
        if let Some(b) = builtin(&format!("{name}.{}", m.name)) {
            return Some(b);
        }
    }
    builtin(name)
}

fn builtin(spelling: &str) -> Option<Symbol<'static>> {
    Builtin::SPELLINGS
        .iter()
        .find(|(s, _)| *s == spelling)
        .map(|(s, b)| Symbol::Builtin(s, *b))
}

fn callee(name: &str) -> Option<Symbol<'static>> {
    if let Some(op) = npr_stdlib::find(name) {
        return Some(Symbol::Operator(op));
    }
    if let Some((n, i)) = Intrinsic::TABLE.iter().find(|(n, _)| *n == name) {
        return Some(Symbol::Intrinsic(n, *i));
    }
    npr_compiler::describe::language::SPECIAL_CALLS
        .iter()
        .find(|(n, ..)| *n == name)
        .map(|(_, written, what)| Symbol::Special(written, what))
}
