//! The WGSL a module includes as written (the emitter's helpers, the
//! stdlib's snippets and operators) split into its functions, and of each
//! function that takes a texture or sampler, the copies a tiled module
//! (`super`) calls: one per set of bindings it is called with, the handle
//! parameters replaced by those bindings.
//!
//! Why copies: a tiled pass answers `textureLoad(t, q, 0)` from a workgroup
//! tile when `t` is a tiled target. Inside a stdlib operator `t` is a
//! parameter, and WGSL cannot tell which binding a parameter is; in a copy
//! every texture is a binding, so its loads are redirected per binding by
//! name. The emitter knows the bindings of every call it writes (the IR's
//! arguments) and calls the copy by its name ([`copy_name`]); a copy's own
//! calls of functions that take handles call their copies in turn.
//!
//! Only library text is read here, never what the emitter wrote: the
//! scanner knows just enough WGSL for the stdlib and the helpers (`//` and
//! `/* */` comments, identifiers, brackets). The tests split every snippet,
//! operator and helper and copy each function that takes handles; whatever
//! it produces is validated by naga like every emitted module, so a case it
//! misreads is an internal error, never a wrong image.

use crate::back::emit::copy_name;
use std::collections::BTreeMap;

/// A top-level function: of the library, or one the emitter writes beside
/// it in a tiled module.
#[derive(Debug, Clone)]
pub(super) struct Function {
    /// The `//` comment lines directly above it (its doc and, for a stdlib
    /// operator, the emitter's `// ---- stdlib operator` header): they go
    /// wherever the function goes, so that no comment is left describing a
    /// function that is elsewhere or not emitted.
    pub doc: String,
    pub name: String,
    /// Parameters as (name, type text).
    pub params: Vec<(String, String)>,
    /// From after the parameter list's `)` to the end of the body's `}`.
    pub rest: String,
}

impl Function {
    fn handle_params(&self) -> Vec<usize> {
        (0..self.params.len())
            .filter(|i| is_handle(&self.params[*i].1))
            .collect()
    }

    /// Whether it takes a texture or sampler: a tiled module calls its
    /// copies, never itself.
    pub fn takes_handles(&self) -> bool {
        self.params.iter().any(|(_, ty)| is_handle(ty))
    }

    /// Its WGSL, doc included, the parameters on one line.
    pub fn text(&self) -> String {
        format!(
            "{}fn {}({}){}",
            self.doc,
            self.name,
            join_params(&self.params),
            self.rest
        )
    }
}

fn is_handle(ty: &str) -> bool {
    let ty = ty.trim();
    ty.starts_with("texture_") || ty.starts_with("sampler")
}

fn join_params(params: &[(String, String)]) -> String {
    params
        .iter()
        .map(|(n, t)| format!("{n}: {}", t.trim()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A tiled module's text, in order: its functions and the text between
/// them (declarations, comments that belong to no function, blank lines),
/// [`split`] from the library or written as such by the emitter.
#[derive(Debug, Clone)]
pub(super) enum Piece {
    Text(String),
    Function(Function),
}

/// The copies one module calls, made from the library's functions as they
/// are asked for.
pub(super) struct Copies<'a> {
    /// The functions that take handles, by name.
    generic: BTreeMap<&'a str, &'a Function>,
    /// `redirect(builtin, binding)`: the function that replaces
    /// `textureLoad(binding, …)` or `textureDimensions(binding, …)` (the
    /// `builtin`) in the copies, called with the other arguments; `None`
    /// keeps the builtin.
    redirect: &'a dyn Fn(&str, &str) -> Option<String>,
    /// The copies made, by name.
    made: BTreeMap<String, String>,
}

impl<'a> Copies<'a> {
    pub fn new(pieces: &'a [Piece], redirect: &'a dyn Fn(&str, &str) -> Option<String>) -> Copies<'a> {
        let generic = pieces
            .iter()
            .filter_map(|p| match p {
                Piece::Function(f) if f.takes_handles() => Some((f.name.as_str(), f)),
                _ => None,
            })
            .collect();
        Copies {
            generic,
            redirect,
            made: BTreeMap::new(),
        }
    }

    /// Makes the copy of `function` bound to `bindings` (and the copies it
    /// calls), once; `Err` says why it cannot be made (an internal error
    /// to the caller).
    pub fn make(&mut self, function: &str, bindings: &[String]) -> Result<(), String> {
        self.instantiate(function, bindings, 0).map(|_| ())
    }

    /// The copies, in name order.
    pub fn texts(&self) -> impl Iterator<Item = &str> {
        self.made.values().map(String::as_str)
    }

    /// The copy of `name` with its handle parameters bound to `globals` (in
    /// parameter order); made once, named by [`copy_name`].
    fn instantiate(&mut self, name: &str, globals: &[String], depth: usize) -> Result<String, String> {
        let copy = copy_name(name, globals);
        if self.made.contains_key(&copy) {
            return Ok(copy);
        }
        if depth > 32 {
            return Err(format!("handle calls nest deeper than 32 at `{name}`"));
        }
        let f = *self
            .generic
            .get(name)
            .ok_or_else(|| format!("no function `{name}` takes a texture or sampler"))?;
        let handles = f.handle_params();
        if handles.len() != globals.len() {
            return Err(format!(
                "`{name}` takes {} handles, bound to {}",
                handles.len(),
                globals.len()
            ));
        }
        let bound: BTreeMap<String, String> = handles
            .iter()
            .zip(globals)
            .map(|(i, g)| (f.params[*i].0.clone(), g.clone()))
            .collect();
        let kept: Vec<(String, String)> = f
            .params
            .iter()
            .enumerate()
            .filter(|(i, _)| !handles.contains(i))
            .map(|(_, p)| p.clone())
            .collect();
        // Reserve the name first: a recursive call would otherwise copy it
        // again (WGSL forbids recursion, naga would report it).
        self.made.insert(copy.clone(), String::new());
        let rest = self.rewrite_body(&f.rest, &bound, depth + 1)?;
        let text = Function {
            doc: f.doc.clone(),
            name: copy.clone(),
            params: kept,
            rest,
        }
        .text();
        self.made.insert(copy.clone(), text);
        Ok(copy)
    }

    /// `body` with bound handle names replaced by their globals, calls of
    /// handle-taking functions replaced by calls of their copies, and
    /// `textureLoad(g, …)` and `textureDimensions(g, …)` of a redirected
    /// global `g` redirected.
    fn rewrite_body(&mut self, body: &str, bound: &BTreeMap<String, String>, depth: usize) -> Result<String, String> {
        let tokens = tokenize(body)?;
        let mut out = String::new();
        let mut i = 0;
        while i < tokens.len() {
            let t = &tokens[i];
            let Token::Ident(id) = t else {
                out.push_str(t.text());
                i += 1;
                continue;
            };
            let open = next_significant(&tokens, i + 1).filter(|o| matches!(&tokens[*o], Token::Punct(p) if p == "("));
            let callee = self.generic.get(id.as_str()).copied();
            if let (Some(f), Some(open)) = (callee, open) {
                let (args, close) = call_args(&tokens, open)?;
                if args.len() != f.params.len() {
                    return Err(format!(
                        "`{id}` called with {} arguments, declared with {}",
                        args.len(),
                        f.params.len()
                    ));
                }
                let mut globals = Vec::new();
                let mut kept_args = Vec::new();
                for (k, arg) in args.iter().enumerate() {
                    let text = self.rewrite_body(arg, bound, depth)?;
                    if is_handle(&f.params[k].1) {
                        let name = text.trim().to_string();
                        if !is_identifier(&name) {
                            return Err(format!("handle argument `{name}` of `{id}` is not a name"));
                        }
                        globals.push(name);
                    } else {
                        kept_args.push(text.trim().to_string());
                    }
                }
                let copy = self.instantiate(id, &globals, depth)?;
                out.push_str(&format!("{copy}({})", kept_args.join(", ")));
                i = close + 1;
                continue;
            }
            if let (true, Some(open)) = (id == "textureLoad" || id == "textureDimensions", open) {
                let (args, close) = call_args(&tokens, open)?;
                let first = args.first().map(|a| a.trim().to_string()).unwrap_or_default();
                let global = bound.get(&first).cloned().unwrap_or(first);
                if let Some(load) = (self.redirect)(id, &global) {
                    let rest: Vec<String> = args[1..]
                        .iter()
                        .map(|a| self.rewrite_body(a, bound, depth).map(|s| s.trim().to_string()))
                        .collect::<Result<_, _>>()?;
                    out.push_str(&format!("{load}({})", rest.join(", ")));
                    i = close + 1;
                    continue;
                }
            }
            out.push_str(bound.get(id).map_or(id.as_str(), |g| g.as_str()));
            i += 1;
        }
        Ok(out)
    }
}

fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The index of the first token at or after `from` that is not blank or a comment.
fn next_significant(tokens: &[Token], from: usize) -> Option<usize> {
    (from..tokens.len()).find(|k| !matches!(tokens[*k], Token::Blank(_)))
}

/// The argument texts of the call whose `(` is `tokens[open]`, split at
/// top-level commas, and the index of its `)`.
fn call_args(tokens: &[Token], open: usize) -> Result<(Vec<String>, usize), String> {
    let mut depth = 0usize;
    let mut args = vec![String::new()];
    for (k, t) in tokens.iter().enumerate().skip(open) {
        match t {
            Token::Punct(p) if p == "(" || p == "[" || p == "{" => {
                depth += 1;
                if depth == 1 {
                    continue;
                }
            }
            Token::Punct(p) if p == ")" || p == "]" || p == "}" => {
                depth -= 1;
                if depth == 0 {
                    if args.len() == 1 && args[0].trim().is_empty() {
                        args.clear();
                    }
                    return Ok((args, k));
                }
            }
            Token::Punct(p) if p == "," && depth == 1 => {
                args.push(String::new());
                continue;
            }
            _ => {}
        }
        args.last_mut().expect("one argument at least").push_str(t.text());
    }
    Err("unclosed call".into())
}

#[derive(Debug, Clone)]
enum Token {
    Ident(String),
    /// Whitespace or a comment.
    Blank(String),
    /// Anything else, one character (or a run of non-bracket characters).
    Punct(String),
}

impl Token {
    fn text(&self) -> &str {
        match self {
            Token::Ident(s) | Token::Blank(s) | Token::Punct(s) => s,
        }
    }
}

fn tokenize(s: &str) -> Result<Vec<Token>, String> {
    let b = s.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let start = i;
        if c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
            out.push(Token::Blank(s[start..i].to_string()));
        } else if c == b'/' && b.get(i + 1) == Some(&b'*') {
            let end = s[i + 2..].find("*/").ok_or("unclosed block comment")?;
            i += 2 + end + 2;
            out.push(Token::Blank(s[start..i].to_string()));
        } else if c.is_ascii_whitespace() {
            while i < b.len() && b[i].is_ascii_whitespace() {
                i += 1;
            }
            out.push(Token::Blank(s[start..i].to_string()));
        } else if c.is_ascii_alphabetic() || c == b'_' {
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                i += 1;
            }
            out.push(Token::Ident(s[start..i].to_string()));
        } else if c.is_ascii_digit() {
            // A number with its suffix (`1u`, `2.5e-3f`): never an identifier.
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'.' || b[i] == b'_') {
                let exp_sign = (b[i] == b'e' || b[i] == b'E') && matches!(b.get(i + 1), Some(b'-' | b'+'));
                i += if exp_sign { 2 } else { 1 };
            }
            out.push(Token::Punct(s[start..i].to_string()));
        } else {
            // One UTF-8 character.
            let len = s[i..].chars().next().map_or(1, char::len_utf8);
            i += len;
            out.push(Token::Punct(s[start..i].to_string()));
        }
    }
    Ok(out)
}

/// Splits library text into its top-level functions and the text between
/// them; `Err` when it is not WGSL the scanner can split.
pub(super) fn split(text: &str) -> Result<Vec<Piece>, String> {
    let tokens = tokenize(text)?;
    let mut pieces = Vec::new();
    let mut between = String::new();
    let mut depth = 0usize;
    // Where in `between` the run of `//` lines just above the next token
    // starts (no blank line, no code in between): the next `fn`'s doc.
    let mut doc_start: Option<usize> = None;
    let mut i = 0;
    while i < tokens.len() {
        let t = &tokens[i];
        if depth == 0 && matches!(t, Token::Ident(k) if k == "fn") {
            let doc = doc_start.take().map(|at| between.split_off(at)).unwrap_or_default();
            let name_at = next_significant(&tokens, i + 1).ok_or("`fn` without a name")?;
            let Token::Ident(name) = &tokens[name_at] else {
                return Err("`fn` without a name".into());
            };
            let open = next_significant(&tokens, name_at + 1).ok_or("`fn` without parameters")?;
            let (param_texts, close) = call_args(&tokens, open)?;
            let mut params = Vec::new();
            for p in param_texts {
                let (n, ty) = p
                    .split_once(':')
                    .ok_or_else(|| format!("parameter `{p}` of `{name}` has no type"))?;
                params.push((n.trim().to_string(), ty.trim().to_string()));
            }
            // The body: from after `)` to the matching `}`.
            let mut k = close + 1;
            let mut rest = String::new();
            let mut body_depth = 0usize;
            let mut seen_body = false;
            while k < tokens.len() {
                let tk = &tokens[k];
                rest.push_str(tk.text());
                match tk {
                    Token::Punct(p) if p == "{" => {
                        body_depth += 1;
                        seen_body = true;
                    }
                    Token::Punct(p) if p == "}" => {
                        body_depth = body_depth.checked_sub(1).ok_or("unbalanced `}`")?;
                        if seen_body && body_depth == 0 {
                            break;
                        }
                    }
                    _ => {}
                }
                k += 1;
            }
            if !seen_body || body_depth != 0 {
                return Err(format!("function `{name}` has no complete body"));
            }
            if !between.is_empty() {
                pieces.push(Piece::Text(std::mem::take(&mut between)));
            }
            pieces.push(Piece::Function(Function {
                doc,
                name: name.clone(),
                params,
                rest,
            }));
            i = k + 1;
            continue;
        }
        match t {
            Token::Punct(p) if p == "{" => depth += 1,
            Token::Punct(p) if p == "}" => depth = depth.checked_sub(1).ok_or("unbalanced `}`")?,
            _ => {}
        }
        doc_start = match t {
            Token::Blank(c) if c.starts_with("//") => doc_start.or(Some(between.len())),
            // Line ends inside the run; a blank line ends it.
            Token::Blank(w) if !w.starts_with("/*") && w.matches('\n').count() <= 1 => doc_start,
            _ => None,
        };
        between.push_str(t.text());
        i += 1;
    }
    if !between.is_empty() {
        pieces.push(Piece::Text(between));
    }
    Ok(pieces)
}

#[cfg(test)]
mod tests {
    use super::*;

    const MODULE: &str = "// a comment with fn and { braces
fn load1(src: texture_2d<f32>, q: vec2<i32>) -> vec4<f32> {
    return textureLoad(src, q, 0) + vec4<f32>(f32(textureDimensions(src).x));
}
fn twice(t: texture_2d<f32>, q: vec2<i32>) -> vec4<f32> {
    /* block */ return load1(t, q) + load1( t , q + vec2<i32>(1, 0));
}
fn plain(x: f32) -> f32 { return x * 2.0e-3; }
";

    fn functions(pieces: &[Piece]) -> Vec<&Function> {
        pieces
            .iter()
            .filter_map(|p| match p {
                Piece::Function(f) => Some(f),
                Piece::Text(_) => None,
            })
            .collect()
    }

    fn copies(
        module: &str,
        function: &str,
        bindings: &[&str],
        redirect: &dyn Fn(&str, &str) -> Option<String>,
    ) -> String {
        let pieces = split(module).unwrap();
        let mut copies = Copies::new(&pieces, redirect);
        let bindings: Vec<String> = bindings.iter().map(|b| b.to_string()).collect();
        copies.make(function, &bindings).unwrap();
        copies.texts().collect::<Vec<_>>().join("\n")
    }

    #[test]
    fn copies_replace_handle_parameters_and_redirect_loads() {
        let out = copies(MODULE, "twice", &["t_a"], &|b, g| {
            (b == "textureLoad" && g == "t_a").then(|| "tile_a".to_string())
        });
        assert!(out.contains("fn twice__t_a(q: vec2<i32>)"), "{out}");
        assert!(out.contains("fn load1__t_a(q: vec2<i32>)"), "{out}");
        assert!(out.contains("return tile_a(q, 0)"), "{out}");
        assert!(out.contains("textureDimensions(t_a)"), "{out}");
        assert!(out.contains("load1__t_a(q + vec2<i32>(1, 0))"), "{out}");
        // The comment above `load1` is its doc: it goes with the copy.
        assert!(
            out.contains("// a comment with fn and { braces\nfn load1__t_a("),
            "{out}"
        );
        assert!(!out.contains("plain"), "{out}");
    }

    #[test]
    fn dimensions_are_redirected_with_their_own_name() {
        let out = copies(MODULE, "load1", &["t_a"], &|b, g| {
            (g == "t_a").then(|| match b {
                "textureLoad" => "tile_a".to_string(),
                _ => "dims_a".to_string(),
            })
        });
        assert!(
            out.contains("return tile_a(q, 0) + vec4<f32>(f32(dims_a().x))"),
            "{out}"
        );
        assert!(!out.contains("textureDimensions"), "{out}");
    }

    #[test]
    fn without_a_redirect_loads_stay() {
        let out = copies(MODULE, "load1", &["t_a"], &|_, _| None);
        assert!(out.contains("textureLoad(t_a, q, 0)"), "{out}");
    }

    #[test]
    fn a_functions_comment_is_its_doc_and_a_detached_one_is_text() {
        let module = "// about the module\n\n// ---- header\n// doc of gen\nfn gen(t: texture_2d<f32>) -> f32 { return 1.0; }\n\n// doc of user\nfn user() -> f32 { return 2.0; }\n";
        let pieces = split(module).unwrap();
        let fs = functions(&pieces);
        assert_eq!(fs[0].doc, "// ---- header\n// doc of gen\n");
        assert_eq!(fs[1].doc, "// doc of user\n");
        assert!(fs[0].takes_handles() && !fs[1].takes_handles());
        assert!(
            matches!(&pieces[0], Piece::Text(t) if t == "// about the module\n\n"),
            "{pieces:?}"
        );
        // Put back together, the pieces are the text.
        let joined: String = pieces
            .iter()
            .map(|p| match p {
                Piece::Text(t) => t.clone(),
                Piece::Function(f) => f.text(),
            })
            .collect();
        assert_eq!(joined, module);
    }

    #[test]
    fn unsplittable_text_is_an_error() {
        assert!(split("fn f(x: f32) -> f32 { return x;").is_err());
        assert!(split("fn f(x) { }").is_err());
    }

    #[test]
    fn an_unknown_function_or_a_wrong_binding_count_is_an_error() {
        let pieces = split(MODULE).unwrap();
        let mut copies = Copies::new(&pieces, &|_, _| None);
        assert!(copies.make("plain", &["t_a".to_string()]).is_err());
        assert!(copies.make("load1", &[]).is_err());
    }

    /// Every piece of WGSL a module includes as written splits, and each of
    /// its functions that take handles can be copied (with the functions
    /// of every other piece beside it, as in a module that includes them
    /// all): the scanner knows enough of the library's WGSL.
    #[test]
    fn every_library_function_splits_and_copies() {
        let mut texts: Vec<String> = npr_stdlib::snippets::ALL.iter().map(|(_, s)| s.to_string()).collect();
        texts.extend(npr_stdlib::all().iter().map(|o| o.wgsl.to_string()));
        texts.extend(crate::back::emit::helpers::library_texts());
        let mut pieces = Vec::new();
        for text in &texts {
            pieces.extend(split(text).unwrap_or_else(|why| panic!("{why}:\n{text}")));
        }
        let generic: Vec<&Function> = functions(&pieces).into_iter().filter(|f| f.takes_handles()).collect();
        assert!(generic.len() > 20, "{} functions take handles", generic.len());
        let mut copies = Copies::new(&pieces, &|_, _| None);
        for f in generic {
            let bindings: Vec<String> = (0..f.handle_params().len()).map(|i| format!("g{i}")).collect();
            copies
                .make(&f.name, &bindings)
                .unwrap_or_else(|why| panic!("`{}`: {why}", f.name));
        }
    }
}
