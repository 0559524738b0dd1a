//! The compile a page asks for, in plain Rust so that it is tested natively
//! as well as in the browser: a style's text and the files it names, held
//! in memory ([`npr_diag::files::MemoryFiles`] under
//! [`PathPolicy::in_memory`]), through `npr_compiler::compile_source`; the
//! result as `npr compile -o DIR` writes it (the WGSL of each pass, the
//! manifest as pretty JSON), or the diagnostics as
//! `--message-format json` gives them.

use npr_compiler::{CompileError, CompileOptions};
use npr_diag::files::{Files, MemoryFiles};
use npr_diag::paths::PathPolicy;
use npr_diag::{codes, Diagnostic, SourceMap};
use serde_json::Value;
use std::path::Path;

/// The name a style has when the page gives none.
pub const DEFAULT_NAME: &str = "style.npr";

/// One style to compile.
#[derive(Debug, Clone)]
pub struct Request {
    /// The style's file name, relative to the in-memory root
    /// (`toon.npr`, `styles/toon.npr`): what diagnostics name, and the
    /// directory its relative paths start from.
    pub name: String,
    pub source: String,
    /// The files it may name, each relative to the root.
    pub files: Vec<(String, Vec<u8>)>,
    /// Keep every live parameter as a uniform (`npr compile --keep-params`),
    /// so that `setParam` can change it.
    pub keep_params: bool,
}

/// A compiled style.
#[derive(Debug, Clone)]
pub struct Output {
    pub manifest: npr_abi::Manifest,
    /// (file name, WGSL) per live pass, in execution order.
    pub shaders: Vec<(String, String)>,
    /// The warnings, one JSON object each.
    pub warnings: Vec<Value>,
}

impl Output {
    /// The manifest as `npr compile -o DIR` writes `manifest.json`.
    pub fn manifest_json(&self) -> String {
        serde_json::to_string_pretty(&self.manifest).unwrap_or_default()
    }
}

/// Why a style did not compile: its diagnostics, one JSON object each
/// (file, line, column, code, message, labels, help, rendered), the first
/// being an error.
#[derive(Debug, Clone)]
pub struct Failure {
    pub diagnostics: Vec<Value>,
}

impl Failure {
    /// One diagnostic with no source to point into.
    pub fn of(d: Diagnostic) -> Failure {
        Failure::from_diagnostics(&[d], &SourceMap::new())
    }

    /// `diags` as JSON, errors first (in their order), then the rest.
    pub fn from_diagnostics(diags: &[Diagnostic], sources: &SourceMap) -> Failure {
        let (errors, others): (Vec<&Diagnostic>, Vec<&Diagnostic>) = diags.iter().partition(|d| d.is_error());
        let ordered: Vec<Diagnostic> = errors.into_iter().chain(others).cloned().collect();
        Failure {
            diagnostics: as_json(&ordered, sources),
        }
    }

    /// The first diagnostic (an error), as the summary of the failure.
    pub fn first(&self) -> &Value {
        self.diagnostics.first().unwrap_or(&Value::Null)
    }
}

/// `diags` as the JSON objects `render_json` writes, one per line.
fn as_json(diags: &[Diagnostic], sources: &SourceMap) -> Vec<Value> {
    npr_diag::diagnostic::render_json(diags, sources)
        .lines()
        .filter_map(|line| serde_json::from_str(line).ok())
        .collect()
}

/// Compile `request`: every file it names is read from its `files` alone,
/// under the paths policy of a style held in memory.
pub fn compile(request: &Request) -> Result<Output, Failure> {
    let name_path = Path::new(&request.name);
    let normalized = npr_diag::files::lexical(name_path);
    if request.name.is_empty() || !npr_diag::files::lexically_inside_root(&normalized) {
        return Err(Failure::of(
            Diagnostic::error(
                codes::BAD_ARGUMENT_VALUE,
                format!("the style's name `{}` is not a relative file name", request.name),
            )
            .with_help("name the style as its file, relative to the files given with it: `toon.npr`"),
        ));
    }
    let mut files = MemoryFiles::new();
    for (path, bytes) in &request.files {
        if let Err(why) = files.insert(path, bytes.clone()) {
            return Err(Failure::of(
                Diagnostic::error(codes::BAD_ARGUMENT_VALUE, format!("a file given with the style: {why}"))
                    .with_help("name each file relative to the style's directory, as the style names it"),
            ));
        }
    }
    let opts = CompileOptions {
        keep_params: request.keep_params,
        paths: Some(PathPolicy::in_memory()),
        files: Files::new(files),
        ..Default::default()
    };
    let dir = normalized.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut sources = SourceMap::new();
    match npr_compiler::compile_source(&request.name, &request.source, &dir, &mut sources, &opts) {
        Ok(c) => Ok(Output {
            warnings: as_json(&c.warnings, &sources),
            manifest: c.manifest,
            shaders: c.shaders,
        }),
        Err(CompileError::User(diags)) => Err(Failure::from_diagnostics(&diags, &sources)),
        Err(CompileError::Internal(e)) => Err(Failure::from_diagnostics(&[e.to_diagnostic()], &sources)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(name: &str, source: &str, files: &[(&str, &str)]) -> Request {
        Request {
            name: name.into(),
            source: source.into(),
            files: files
                .iter()
                .map(|(p, t)| (p.to_string(), t.as_bytes().to_vec()))
                .collect(),
            keep_params: true,
        }
    }

    const STYLE: &str =
        "style \"S\"\nuse \"lib/a.npr\"\npass final: image() {\n  out color: rgba8unorm = vec4(a, a, a, 1.0)\n}\noutput final.color\n";

    #[test]
    fn a_style_and_its_files_compile_from_memory() {
        let lib = [("lib/a.npr", "style \"A\"\nparam a: float = 0.5 in 0..1\n")];
        let out = compile(&request("s.npr", STYLE, &lib)).expect("compiles");
        assert!(!out.shaders.is_empty());
        assert!(out.manifest_json().contains("\"a\""), "{}", out.manifest_json());
        // The same style one folder down finds its library there.
        let lib = [("styles/lib/a.npr", lib[0].1)];
        compile(&request("styles/s.npr", STYLE, &lib)).expect("compiles in a folder");
    }

    #[test]
    fn a_bad_name_or_file_path_is_refused_before_compiling() {
        for name in ["", "../s.npr", "/s.npr"] {
            let f = compile(&request(name, STYLE, &[])).expect_err(name);
            assert_eq!(f.first()["code"], codes::BAD_ARGUMENT_VALUE, "{name}");
        }
        let f = compile(&request("s.npr", STYLE, &[("../lib/a.npr", "")])).expect_err("outside");
        assert_eq!(f.first()["code"], codes::BAD_ARGUMENT_VALUE);
        assert!(f.first()["message"]
            .as_str()
            .is_some_and(|m| m.contains("../lib/a.npr")));
    }

    #[test]
    fn errors_come_first_with_their_line_and_column() {
        let f = compile(&request("s.npr", STYLE, &[])).expect_err("no library");
        let first = f.first();
        assert_eq!(first["code"], codes::BAD_USE, "{first}");
        let label = &first["labels"][0];
        assert_eq!(
            (&label["file"], &label["line"], &label["column"]),
            (&"s.npr".into(), &2.into(), &1.into()),
            "{first}"
        );
        assert!(f.diagnostics.iter().all(|d| d["rendered"].is_string()));
    }
}
