//! The parser pest derives from `grammar.pest`, and its `Rule`s. Its own
//! module because two others read the rules: the parser builds the AST
//! from them and `syntax_error` names them in messages; neither imports
//! the other for them.

#[derive(pest_derive::Parser)]
#[grammar = "grammar.pest"]
pub(crate) struct NprParser;
