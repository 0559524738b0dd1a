//! Handle monomorphization of a WGSL module: every function that takes a
//! texture or sampler parameter is copied once per set of module-scope
//! handles it is called with, the parameters replaced by those globals.
//!
//! Why: a tiled pass (`super`) answers `textureLoad(t, q, 0)` from a
//! workgroup tile when `t` is a tiled target. Inside a stdlib operator `t`
//! is a parameter, and WGSL cannot tell which binding a parameter is; after
//! this rewrite every texture in every function body is a global, so the
//! load can be redirected per binding by name. Functions without handle
//! parameters are kept as they are; the generic originals are dropped (no
//! caller is left).
//!
//! The scanner knows just enough WGSL for the stdlib and the emitter's
//! output: `//` and `/* */` comments, identifiers, brackets. Whatever it
//! produces is validated by naga like every emitted module, so a case it
//! misreads is an internal error in the tests, never a wrong image.

use std::collections::BTreeMap;

/// One top-level function of the module.
#[derive(Debug, Clone)]
struct Function {
    /// The `//` comment lines directly above the function (its doc and,
    /// for a stdlib operator, the emitter's `// ---- stdlib operator`
    /// header), moved with it so that no comment is left describing a
    /// function that is now elsewhere or gone.
    doc: String,
    /// Parameters as (name, type text).
    params: Vec<(String, String)>,
    /// From after the parameter list's `)` to the end of the body's `}`.
    rest: String,
}

impl Function {
    fn handle_params(&self) -> Vec<usize> {
        (0..self.params.len())
            .filter(|i| is_handle(&self.params[*i].1))
            .collect()
    }
}

fn is_handle(ty: &str) -> bool {
    let ty = ty.trim();
    ty.starts_with("texture_") || ty.starts_with("sampler")
}

/// A module split into its functions and everything else (kept verbatim).
struct Module {
    /// Top-level text that is not a function, in order.
    other: String,
    /// Functions by name, in order of appearance.
    functions: Vec<(String, Function)>,
}

/// Rewrites `module` so that no function takes a handle parameter: see the
/// module doc. `rename_load(builtin, global)` names the function that
/// replaces `textureLoad(global, …)` or `textureDimensions(global, …)` (the
/// `builtin`) in the copies, called with the other arguments (`None` keeps
/// the builtin).
/// Returns `Err` with a reason when the text is not WGSL the scanner can
/// split (an internal error to the caller).
pub fn monomorphize(module: &str, rename_load: &dyn Fn(&str, &str) -> Option<String>) -> Result<String, String> {
    let parsed = split_module(module)?;
    let by_name: BTreeMap<&str, &Function> = parsed.functions.iter().map(|(n, f)| (n.as_str(), f)).collect();
    let mut copies: BTreeMap<String, String> = BTreeMap::new();
    let mut kept = String::new();
    for (name, f) in &parsed.functions {
        if !f.handle_params().is_empty() {
            continue;
        }
        let rest = rewrite_body(&f.rest, &BTreeMap::new(), &by_name, &mut copies, rename_load, 0)?;
        kept.push_str(&format!("{}fn {name}({}){rest}\n\n", f.doc, join_params(&f.params)));
    }
    let mut out = parsed.other;
    out.push_str(&kept);
    for text in copies.values() {
        out.push_str(text);
        out.push_str("\n\n");
    }
    Ok(collapse_blank_lines(&out))
}

/// `text` with every run of blank lines shortened to one: the functions
/// taken out of the module leave their line breaks behind.
fn collapse_blank_lines(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut blank_run = 0;
    for line in text.split_inclusive('\n') {
        blank_run = if line.trim().is_empty() { blank_run + 1 } else { 0 };
        if blank_run <= 1 {
            out.push_str(line);
        }
    }
    out
}

fn join_params(params: &[(String, String)]) -> String {
    params
        .iter()
        .map(|(n, t)| format!("{n}: {}", t.trim()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The copy of `name` with its handle parameters bound to `globals` (in
/// parameter order); made once, named after the globals.
fn instantiate(
    name: &str,
    globals: &[String],
    by_name: &BTreeMap<&str, &Function>,
    copies: &mut BTreeMap<String, String>,
    rename_load: &dyn Fn(&str, &str) -> Option<String>,
    depth: usize,
) -> Result<String, String> {
    let copy_name = format!("{name}__{}", globals.join("__"));
    if copies.contains_key(&copy_name) {
        return Ok(copy_name);
    }
    if depth > 32 {
        return Err(format!("handle calls nest deeper than 32 at `{name}`"));
    }
    let f = by_name[name];
    let handles = f.handle_params();
    let mut bound: BTreeMap<String, String> = BTreeMap::new();
    for (k, i) in handles.iter().enumerate() {
        bound.insert(f.params[*i].0.clone(), globals[k].clone());
    }
    let kept: Vec<(String, String)> = f
        .params
        .iter()
        .enumerate()
        .filter(|(i, _)| !handles.contains(i))
        .map(|(_, p)| p.clone())
        .collect();
    // Reserve the name first: a recursive call would otherwise instantiate
    // it again (WGSL forbids recursion, naga would report it).
    copies.insert(copy_name.clone(), String::new());
    let rest = rewrite_body(&f.rest, &bound, by_name, copies, rename_load, depth + 1)?;
    copies.insert(
        copy_name.clone(),
        format!("{}fn {copy_name}({}){rest}", f.doc, join_params(&kept)),
    );
    Ok(copy_name)
}

/// `body` with bound handle names replaced by their globals, calls of
/// handle-taking functions replaced by calls of their copies, and
/// `textureLoad(g, …)` and `textureDimensions(g, …)` of a renamed global
/// `g` redirected.
fn rewrite_body(
    body: &str,
    bound: &BTreeMap<String, String>,
    by_name: &BTreeMap<&str, &Function>,
    copies: &mut BTreeMap<String, String>,
    rename_load: &dyn Fn(&str, &str) -> Option<String>,
    depth: usize,
) -> Result<String, String> {
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
        let open = next_significant(&tokens, i + 1);
        let is_call = open.is_some_and(|o| matches!(&tokens[o], Token::Punct(p) if p == "("));
        let callee = by_name.get(id.as_str()).filter(|f| !f.handle_params().is_empty());
        if let (true, Some(f), Some(open)) = (is_call, callee, open) {
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
                let text = rewrite_body(arg, bound, by_name, copies, rename_load, depth)?;
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
            let copy = instantiate(id, &globals, by_name, copies, rename_load, depth)?;
            out.push_str(&format!("{copy}({})", kept_args.join(", ")));
            i = close + 1;
            continue;
        }
        if (id == "textureLoad" || id == "textureDimensions") && is_call {
            let open = open.unwrap_or(i + 1);
            let (args, close) = call_args(&tokens, open)?;
            let first = args.first().map(|a| a.trim().to_string()).unwrap_or_default();
            let global = bound.get(&first).cloned().unwrap_or(first);
            if let Some(load) = rename_load(id, &global) {
                let rest: Vec<String> = args[1..]
                    .iter()
                    .map(|a| rewrite_body(a, bound, by_name, copies, rename_load, depth).map(|s| s.trim().to_string()))
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

/// Splits a module into its top-level functions and the rest.
fn split_module(module: &str) -> Result<Module, String> {
    let tokens = tokenize(module)?;
    let mut other = String::new();
    let mut functions = Vec::new();
    let mut depth = 0usize;
    // Where in `other` the run of `//` lines just above the next token
    // starts (no blank line, no code in between): the next `fn`'s doc.
    let mut doc_start: Option<usize> = None;
    let mut i = 0;
    while i < tokens.len() {
        let t = &tokens[i];
        if depth == 0 && matches!(t, Token::Ident(k) if k == "fn") {
            let doc = doc_start.take().map(|at| other.split_off(at)).unwrap_or_default();
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
            functions.push((name.clone(), Function { doc, params, rest }));
            i = k + 1;
            continue;
        }
        match t {
            Token::Punct(p) if p == "{" => depth += 1,
            Token::Punct(p) if p == "}" => depth = depth.checked_sub(1).ok_or("unbalanced `}`")?,
            _ => {}
        }
        doc_start = match t {
            Token::Blank(c) if c.starts_with("//") => doc_start.or(Some(other.len())),
            // Line ends inside the run; a blank line ends it.
            Token::Blank(w) if !w.starts_with("/*") && w.matches('\n').count() <= 1 => doc_start,
            _ => None,
        };
        other.push_str(t.text());
        i += 1;
    }
    Ok(Module { other, functions })
}

#[cfg(test)]
mod tests {
    use super::*;

    const MODULE: &str = "@group(0) @binding(1) var t_a: texture_2d<f32>;
// a comment with fn and { braces
fn load1(src: texture_2d<f32>, q: vec2<i32>) -> vec4<f32> {
    return textureLoad(src, q, 0) + vec4<f32>(f32(textureDimensions(src).x));
}
fn twice(t: texture_2d<f32>, q: vec2<i32>) -> vec4<f32> {
    /* block */ return load1(t, q) + load1( t , q + vec2<i32>(1, 0));
}
fn plain(x: f32) -> f32 { return x * 2.0e-3; }
fn main_px() -> vec4<f32> {
    return twice(t_a, vec2<i32>(0)) + vec4<f32>(plain(1.0));
}
";

    #[test]
    fn copies_replace_handle_parameters_and_redirect_loads() {
        let out = monomorphize(MODULE, &|b, g| {
            (b == "textureLoad" && g == "t_a").then(|| "tile_a".to_string())
        })
        .unwrap();
        assert!(out.contains("fn twice__t_a(q: vec2<i32>)"), "{out}");
        assert!(out.contains("fn load1__t_a(q: vec2<i32>)"), "{out}");
        assert!(out.contains("return tile_a(q, 0)"), "{out}");
        assert!(out.contains("textureDimensions(t_a)"), "{out}");
        assert!(out.contains("load1__t_a(q + vec2<i32>(1, 0))"), "{out}");
        assert!(out.contains("return twice__t_a(vec2<i32>(0))"), "{out}");
        // The generic originals are gone; the comment and binding stay.
        assert!(!out.contains("fn load1(src"), "{out}");
        assert!(
            out.contains("// a comment with fn and { braces\nfn load1__t_a("),
            "{out}"
        );
        assert!(out.contains("fn plain(x: f32)"), "{out}");
    }

    #[test]
    fn dimensions_are_redirected_with_their_own_name() {
        let out = monomorphize(MODULE, &|b, g| {
            (g == "t_a").then(|| match b {
                "textureLoad" => "tile_a".to_string(),
                _ => "dims_a".to_string(),
            })
        })
        .unwrap();
        assert!(
            out.contains("return tile_a(q, 0) + vec4<f32>(f32(dims_a().x))"),
            "{out}"
        );
        assert!(!out.contains("textureDimensions"), "{out}");
    }

    #[test]
    fn a_functions_comment_moves_with_it_and_a_detached_one_stays() {
        let module = "// about the module\n\n// ---- header\n// doc of gen\nfn gen(t: texture_2d<f32>) -> f32 { return 1.0; }\n\n// doc of user\nfn user() -> f32 { return gen(t_a); }\n@group(0) @binding(0) var t_a: texture_2d<f32>;\n";
        let out = monomorphize(module, &|_, _| None).unwrap();
        assert!(out.starts_with("// about the module\n\n"), "{out}");
        assert_eq!(
            out.matches("// ---- header\n// doc of gen\nfn gen__t_a()").count(),
            1,
            "{out}"
        );
        assert!(out.contains("// doc of user\nfn user()"), "{out}");
        // Nothing of gen's comment is left where the generic function was.
        assert_eq!(out.matches("doc of gen").count(), 1, "{out}");
    }

    #[test]
    fn without_a_redirect_loads_stay() {
        let out = monomorphize(MODULE, &|_, _| None).unwrap();
        assert!(out.contains("textureLoad(t_a, q, 0)"), "{out}");
    }

    #[test]
    fn unsplittable_text_is_an_error() {
        assert!(monomorphize("fn f(x: f32) -> f32 { return x;", &|_, _| None).is_err());
        assert!(monomorphize("fn f(x) { }", &|_, _| None).is_err());
    }
}
