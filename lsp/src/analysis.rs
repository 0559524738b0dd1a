//! One open document as the language features see it: its text loaded as
//! the compiler loads a style (the document and every file it `use`s,
//! parsed with recovery), and the declarations of all of them by name.

use npr_compiler::Loaded;
use npr_diag::{FileId, SourceMap, Span};
use npr_dsl::ast::{Item, ParamDecl, PassDecl, TextureDecl};
use std::path::{Path, PathBuf};

pub struct Analysis {
    pub sources: SourceMap,
    pub loaded: Loaded,
}

/// A per-object value or a target a pass makes: its name, its format or
/// type, and where it is declared.
pub struct Target<'a> {
    pub name: &'a str,
    pub kind: &'static str,
    pub ty: &'a str,
    pub span: Span,
}

impl Analysis {
    /// Load `text` as the style at `path` (the parser recovers, so a
    /// document with errors still has the declarations that parse).
    pub fn new(path: &Path, text: &str) -> Analysis {
        let mut sources = SourceMap::new();
        let mut diags = Vec::new();
        let dir = path.parent().unwrap_or(Path::new("."));
        let name = path.display().to_string();
        // Without a policy (the directory is gone) nothing `use`d can be
        // read anyway; `diagnostics::check` reports why.
        let policy = super::policy::for_document(path).ok();
        let loaded = npr_compiler::load_source(&name, text, dir, &mut sources, policy.as_ref(), &mut diags);
        Analysis { sources, loaded }
    }

    pub fn root(&self) -> FileId {
        self.loaded.root_file
    }

    /// Every declaration of the document and of the files it `use`s.
    pub fn items(&self) -> impl Iterator<Item = &Item> {
        self.loaded.items.iter().map(|(item, _)| item)
    }

    pub fn param(&self, name: &str) -> Option<&ParamDecl> {
        self.items().find_map(|i| match i {
            Item::Param(p) if p.name.name == name => Some(p),
            _ => None,
        })
    }

    pub fn texture(&self, name: &str) -> Option<&TextureDecl> {
        self.items().find_map(|i| match i {
            Item::Texture(t) if t.name.name == name => Some(t),
            _ => None,
        })
    }

    pub fn pass(&self, name: &str) -> Option<&PassDecl> {
        self.items().find_map(|i| match i {
            Item::Pass(p) if p.name.name == name => Some(p),
            _ => None,
        })
    }

    /// The file a span is in, as a path.
    pub fn file_path(&self, file: FileId) -> Option<PathBuf> {
        self.sources.get(file).map(|f| PathBuf::from(&f.name))
    }

    pub fn text(&self, file: FileId) -> &str {
        self.sources.get(file).map_or("", |f| f.text.as_str())
    }
}

/// What a pass makes that `pass.name` reads: outputs, reductions, states.
pub fn targets(pass: &PassDecl) -> Vec<Target<'_>> {
    let body = &pass.body;
    let outputs = body.outputs.iter().map(|o| Target {
        name: &o.name.name,
        kind: "out",
        ty: &o.format.name,
        span: o.name.span,
    });
    let reductions = body.reductions.iter().map(|r| Target {
        name: &r.name.name,
        kind: "reduce",
        ty: &r.ty.name,
        span: r.name.span,
    });
    let states = body.states.iter().map(|s| Target {
        name: &s.name.name,
        kind: "state",
        ty: &s.ty.name,
        span: s.name.span,
    });
    outputs.chain(reductions).chain(states).collect()
}

/// The text of `span` in its file.
pub fn snippet(a: &Analysis, span: Span) -> &str {
    a.text(span.file).get(span.range()).unwrap_or("")
}
