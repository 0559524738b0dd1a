//! JSON-RPC over stdio, framed with `Content-Length` by `lsp-server`, but
//! read on this thread so that a malformed message is answered with a
//! parse error and the next one is read, where `lsp-server`'s own stdio
//! thread would stop.

use lsp_server::Message;
use std::io::{BufRead, ErrorKind, Write};

pub enum Incoming {
    Message(Message),
    /// A frame whose body is not a JSON-RPC message, or a bad header line.
    Malformed(String),
    /// Standard input closed.
    End,
}

pub fn read(input: &mut impl BufRead) -> Incoming {
    match Message::read(input) {
        Ok(Some(m)) => Incoming::Message(m),
        Ok(None) => Incoming::End,
        Err(e) if e.kind() == ErrorKind::InvalidData => Incoming::Malformed(e.to_string()),
        Err(_) => Incoming::End,
    }
}

pub fn write(msg: Message) {
    let mut out = std::io::stdout().lock();
    let _ = msg.write(&mut out);
    let _ = out.flush();
}

/// JSON-RPC's answer to a message that cannot be parsed: error -32700 with
/// a null id (its id cannot be known).
pub fn write_parse_error(why: &str) {
    let body = serde_json::json!({
        "jsonrpc": "2.0",
        "id": null,
        "error": { "code": -32700, "message": format!("parse error: {why}") },
    })
    .to_string();
    let mut out = std::io::stdout().lock();
    let _ = write!(out, "Content-Length: {}\r\n\r\n{body}", body.len());
    let _ = out.flush();
}
