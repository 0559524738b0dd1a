//! npr's language server (`npr lsp` runs [`run`]): a language server over stdio (JSON-RPC framed by
//! `lsp-server`). Diagnostics on open and change, hover, completion, go to
//! definition and document symbols for `.npr` documents; diagnostics for a
//! style's `.tests.toml` (`test_file.rs`).
//!
//! The server never exits on bad input: a malformed message gets a
//! JSON-RPC parse error, an unknown method "method not found", bad params
//! "invalid params", a document that is not `.npr` is ignored, and a panic
//! in a handler becomes an internal error for that request. It exits on
//! `exit` or when stdin closes.
//!
//! # Example
//!
//! A program of your own that is the server (what `npr lsp` does):
//!
//! ```no_run
//! // The whole of a program that is the server:
//! std::process::exit(npr_lsp::run());
//! ```

mod analysis;
mod completion;
mod definition;
mod diagnostics;
mod hover;
mod policy;
mod position;
mod symbol;
mod symbols;
mod test_file;
mod tokens;
mod transport;
mod uri;

use analysis::Analysis;
use lsp_server::{ErrorCode, Message, Notification, Request, Response};
use lsp_types::notification::{self as note, Notification as _};
use lsp_types::request::{self as req, Request as _};
use lsp_types::*;
use position::LineIndex;
use std::collections::HashMap;
use std::path::PathBuf;

/// An open `.npr` document, or a style's `.tests.toml`.
struct Document {
    uri: Uri,
    path: PathBuf,
    text: String,
    /// A test file: diagnostics only (no hover, completion or symbols).
    tests: bool,
}

#[derive(Default)]
struct Server {
    initialized: bool,
    shutdown: bool,
    documents: HashMap<String, Document>,
}

/// Serve on stdin/stdout until `exit` or end of input; the exit code.
pub fn run() -> i32 {
    let mut server = Server::default();
    let mut input = std::io::stdin().lock();
    loop {
        match transport::read(&mut input) {
            transport::Incoming::Message(msg) => {
                if let Some(code) = server.handle(msg) {
                    return code;
                }
            }
            transport::Incoming::Malformed(why) => transport::write_parse_error(&why),
            transport::Incoming::End => return if server.shutdown { 0 } else { 1 },
        }
    }
}

impl Server {
    /// Handle one message; `Some(exit code)` when the server should stop.
    fn handle(&mut self, msg: Message) -> Option<i32> {
        match msg {
            Message::Request(r) => {
                let id = r.id.clone();
                let method = r.method.clone();
                let answer =
                    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| self.request(r))).unwrap_or_else(|_| {
                        Err((
                            ErrorCode::InternalError,
                            format!("npr lsp failed on `{method}` (a bug in npr)"),
                        ))
                    });
                let response = match answer {
                    Ok(value) => Response::new_ok(id, value),
                    Err((code, message)) => Response::new_err(id, code as i32, message),
                };
                transport::write(Message::Response(response));
                None
            }
            Message::Notification(n) if n.method == note::Exit::METHOD => Some(if self.shutdown { 0 } else { 1 }),
            Message::Notification(n) => {
                let method = n.method.clone();
                if std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| self.notification(n))).is_err() {
                    log(&format!("npr lsp failed on `{method}` (a bug in npr)"));
                }
                None
            }
            // The server sends no requests, so no response is expected.
            Message::Response(_) => None,
        }
    }

    fn request(&mut self, r: Request) -> Result<serde_json::Value, (ErrorCode, String)> {
        if r.method == req::Initialize::METHOD {
            self.initialized = true;
            return Ok(serde_json::to_value(initialize_result()).unwrap_or_default());
        }
        if !self.initialized {
            return Err((
                ErrorCode::ServerNotInitialized,
                "the first request must be `initialize`".into(),
            ));
        }
        let value = match r.method.as_str() {
            req::Shutdown::METHOD => {
                self.shutdown = true;
                serde_json::Value::Null
            }
            req::HoverRequest::METHOD => {
                let p: HoverParams = params(r)?;
                to_json(self.hover(&p.text_document_position_params))
            }
            req::Completion::METHOD => {
                let p: CompletionParams = params(r)?;
                to_json(self.completion(&p.text_document_position))
            }
            req::GotoDefinition::METHOD => {
                let p: GotoDefinitionParams = params(r)?;
                to_json(self.definition(&p.text_document_position_params))
            }
            req::DocumentSymbolRequest::METHOD => {
                let p: DocumentSymbolParams = params(r)?;
                to_json(self.symbols(&p.text_document.uri))
            }
            other => return Err((ErrorCode::MethodNotFound, format!("npr lsp has no method `{other}`"))),
        };
        Ok(value)
    }

    fn notification(&mut self, n: Notification) {
        match n.method.as_str() {
            note::DidOpenTextDocument::METHOD => {
                let Ok(p) = n.extract::<DidOpenTextDocumentParams>(note::DidOpenTextDocument::METHOD) else {
                    return log("didOpen with bad params: ignored");
                };
                let d = p.text_document;
                self.open(d.uri, &d.language_id, d.text);
            }
            note::DidChangeTextDocument::METHOD => {
                let Ok(p) = n.extract::<DidChangeTextDocumentParams>(note::DidChangeTextDocument::METHOD) else {
                    return log("didChange with bad params: ignored");
                };
                // Full sync: the last change is the whole text.
                let Some(change) = p.content_changes.into_iter().last() else {
                    return;
                };
                let key = p.text_document.uri.as_str().to_string();
                if let Some(doc) = self.documents.get_mut(&key) {
                    doc.text = change.text;
                    self.publish(&key);
                }
            }
            note::DidCloseTextDocument::METHOD => {
                let Ok(p) = n.extract::<DidCloseTextDocumentParams>(note::DidCloseTextDocument::METHOD) else {
                    return;
                };
                if let Some(doc) = self.documents.remove(p.text_document.uri.as_str()) {
                    publish_diagnostics(doc.uri, Vec::new());
                }
            }
            // `initialized`, `$/cancelRequest`, configuration changes...: nothing to do.
            _ => {}
        }
    }

    /// Track a document if it is a style: a path ending in `.npr`, or the
    /// `npr` language (an unsaved one resolves its `use`s against the
    /// working directory).
    fn open(&mut self, uri: Uri, language: &str, text: String) {
        let path = uri::to_path(&uri);
        let tests = path.as_deref().is_some_and(test_file::is_test_file);
        let is_npr = language == "npr" || path.as_ref().is_some_and(|p| p.extension().is_some_and(|e| e == "npr"));
        if !is_npr && !tests {
            return;
        }
        let path = path.unwrap_or_else(|| std::env::current_dir().unwrap_or_default().join("untitled.npr"));
        let key = uri.as_str().to_string();
        self.documents.insert(key.clone(), Document { uri, path, text, tests });
        self.publish(&key);
    }

    fn publish(&self, key: &str) {
        if let Some(doc) = self.documents.get(key) {
            let found = if doc.tests {
                test_file::check(&doc.path, &doc.text)
            } else {
                diagnostics::check(&doc.path, &doc.text)
            };
            publish_diagnostics(doc.uri.clone(), found);
        }
    }

    /// The document, its analysis and the byte offset of a position in it.
    fn at(&self, pos: &TextDocumentPositionParams) -> Option<(&Document, Analysis, usize)> {
        let doc = self
            .documents
            .get(pos.text_document.uri.as_str())
            .filter(|d| !d.tests)?;
        let offset = LineIndex::new(&doc.text).offset(pos.position);
        Some((doc, Analysis::new(&doc.path, &doc.text), offset))
    }

    fn hover(&self, pos: &TextDocumentPositionParams) -> Option<Hover> {
        let (_, a, offset) = self.at(pos)?;
        let (token, pass) = tokens::at(&a.loaded.root, offset)?;
        let symbol = symbol::resolve(&a, &token, pass)?;
        Some(Hover {
            contents: HoverContents::Markup(MarkupContent {
                kind: MarkupKind::Markdown,
                value: hover::markdown(&a, &symbol),
            }),
            range: None,
        })
    }

    fn completion(&self, pos: &TextDocumentPositionParams) -> Option<CompletionResponse> {
        let (doc, a, offset) = self.at(pos)?;
        Some(CompletionResponse::Array(completion::complete(&a, &doc.text, offset)))
    }

    fn definition(&self, pos: &TextDocumentPositionParams) -> Option<GotoDefinitionResponse> {
        let (_, a, offset) = self.at(pos)?;
        let (token, pass) = tokens::at(&a.loaded.root, offset)?;
        let symbol = symbol::resolve(&a, &token, pass)?;
        let span = definition::declared_at(&symbol)?;
        definition::location(&a, span).map(GotoDefinitionResponse::Scalar)
    }

    fn symbols(&self, uri: &Uri) -> Option<DocumentSymbolResponse> {
        let doc = self.documents.get(uri.as_str()).filter(|d| !d.tests)?;
        let a = Analysis::new(&doc.path, &doc.text);
        Some(DocumentSymbolResponse::Nested(symbols::outline(&a)))
    }
}

fn initialize_result() -> InitializeResult {
    InitializeResult {
        capabilities: ServerCapabilities {
            text_document_sync: Some(TextDocumentSyncCapability::Kind(TextDocumentSyncKind::FULL)),
            hover_provider: Some(HoverProviderCapability::Simple(true)),
            completion_provider: Some(CompletionOptions {
                trigger_characters: Some(vec![".".into(), ":".into(), "(".into()]),
                ..CompletionOptions::default()
            }),
            definition_provider: Some(OneOf::Left(true)),
            document_symbol_provider: Some(OneOf::Left(true)),
            position_encoding: Some(PositionEncodingKind::UTF16),
            ..ServerCapabilities::default()
        },
        server_info: Some(ServerInfo {
            name: "npr".into(),
            version: Some(env!("CARGO_PKG_VERSION").into()),
        }),
    }
}

fn params<P: serde::de::DeserializeOwned>(r: Request) -> Result<P, (ErrorCode, String)> {
    serde_json::from_value(r.params)
        .map_err(|e| (ErrorCode::InvalidParams, format!("bad params for `{}`: {e}", r.method)))
}

fn to_json<T: serde::Serialize>(value: Option<T>) -> serde_json::Value {
    value
        .and_then(|v| serde_json::to_value(v).ok())
        .unwrap_or(serde_json::Value::Null)
}

fn publish_diagnostics(uri: Uri, diagnostics: Vec<lsp_types::Diagnostic>) {
    let params = PublishDiagnosticsParams {
        uri,
        diagnostics,
        version: None,
    };
    transport::write(Message::Notification(Notification::new(
        note::PublishDiagnostics::METHOD.into(),
        params,
    )));
}

/// A message in the client's log (`window/logMessage`).
fn log(message: &str) {
    transport::write(Message::Notification(Notification::new(
        note::LogMessage::METHOD.into(),
        LogMessageParams {
            typ: MessageType::WARNING,
            message: message.into(),
        },
    )));
}
