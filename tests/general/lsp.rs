//! `npr lsp` as an editor drives it: the binary spawned, JSON-RPC written
//! to its stdin with `Content-Length` frames and read back from its stdout.
//! Diagnostics (codes, UTF-16 ranges after non-ASCII text), hover,
//! completion, go to definition across a `use`, document symbols, and bad
//! input the server must survive: malformed frames, unknown methods, bad
//! params, documents that are not `.npr`.

use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::Duration;

/// A hang guard, not a measurement.
const HANG: Duration = Duration::from_secs(120);

struct Client {
    child: Child,
    /// `None` once closed.
    stdin: Option<ChildStdin>,
    incoming: Receiver<Value>,
    /// Notifications read while waiting for responses.
    notifications: Vec<Value>,
    next_id: i64,
}

impl Client {
    fn start() -> Client {
        let mut child = Command::new(env!("CARGO_BIN_EXE_npr"))
            .arg("lsp")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("start npr lsp");
        let stdin = child.stdin.take().expect("stdin");
        let mut stdout = BufReader::new(child.stdout.take().expect("stdout"));
        let (tx, incoming) = channel();
        std::thread::spawn(move || loop {
            let mut length = None;
            loop {
                let mut line = String::new();
                if stdout.read_line(&mut line).unwrap_or(0) == 0 {
                    return;
                }
                let line = line.trim_end();
                if line.is_empty() {
                    break;
                }
                if let Some(n) = line.strip_prefix("Content-Length: ") {
                    length = n.parse::<usize>().ok();
                }
            }
            let mut body = vec![0; length.expect("a Content-Length header")];
            if stdout.read_exact(&mut body).is_err() {
                return;
            }
            let value: Value = serde_json::from_slice(&body).expect("the server writes JSON");
            if tx.send(value).is_err() {
                return;
            }
        });
        Client {
            child,
            stdin: Some(stdin),
            incoming,
            notifications: Vec::new(),
            next_id: 1,
        }
    }

    fn send_raw(&mut self, bytes: &[u8]) {
        let stdin = self.stdin.as_mut().expect("stdin open");
        stdin.write_all(bytes).expect("write to the server");
        stdin.flush().expect("flush");
    }

    fn send(&mut self, message: Value) {
        let body = message.to_string();
        self.send_raw(format!("Content-Length: {}\r\n\r\n{body}", body.len()).as_bytes());
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.send(json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    /// Send a request and wait for its response (the whole message).
    fn request_full(&mut self, method: &str, params: Value) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        self.send(json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        self.wait(|m| m.get("id") == Some(&json!(id)))
    }

    /// A request's `result`; fails on an error response.
    fn request(&mut self, method: &str, params: Value) -> Value {
        let r = self.request_full(method, params);
        assert!(r.get("error").is_none(), "{method} failed: {r}");
        r["result"].clone()
    }

    /// The next message that `matches`, keeping the notifications before it.
    fn wait(&mut self, matches: impl Fn(&Value) -> bool) -> Value {
        loop {
            let m = self
                .incoming
                .recv_timeout(HANG)
                .unwrap_or_else(|_| panic!("the server stopped answering; notifications: {:?}", self.notifications));
            if matches(&m) {
                return m;
            }
            if m.get("id").is_none() {
                self.notifications.push(m);
            }
        }
    }

    /// The diagnostics published next for `uri`.
    fn diagnostics(&mut self, uri: &str) -> Vec<Value> {
        let m = self.wait(|m| m["method"] == "textDocument/publishDiagnostics" && m["params"]["uri"] == uri);
        m["params"]["diagnostics"].as_array().cloned().unwrap_or_default()
    }
}

impl Drop for Client {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn uri(path: &Path) -> String {
    let mut s = String::from("file://");
    for b in path.to_str().expect("utf-8 path").bytes() {
        if b.is_ascii_alphanumeric() || b"/-._~".contains(&b) {
            s.push(b as char);
        } else {
            s.push_str(&format!("%{b:02X}"));
        }
    }
    s
}

/// The position of the `nth` occurrence of `needle` in `text` (plus
/// `shift` bytes), in UTF-16 code units as LSP counts them.
fn pos(text: &str, needle: &str, nth: usize, shift: usize) -> Value {
    let at = text
        .match_indices(needle)
        .nth(nth)
        .unwrap_or_else(|| panic!("{needle} in text"))
        .0
        + shift;
    let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    let line = text[..at].matches('\n').count();
    json!({"line": line, "character": text[line_start..at].encode_utf16().count()})
}

fn at(doc: &str, text: &str, needle: &str, nth: usize, shift: usize) -> Value {
    json!({"textDocument": {"uri": doc}, "position": pos(text, needle, nth, shift)})
}

const LIB: &str = "style \"Lib\"\n/// Overall gain.\nparam gain: float = 1.0 in 0..2\n";

/// Non-ASCII in a doc comment, the style name and an inline comment before a name.
const MAIN: &str = "style \"Café\"\nuse \"lib.npr\"\n\n/// Nombre de bandes — «bands» 𝒩.\nparam bands: int = 3 in 1..8\n/// Paper grain.\ntexture grain = noise(size: 64)\n\
pass shade: render(scene) {\n  let lit = half_lambert(normal, light.dir)\n  out color: rgba8unorm = vec4(vec3(toon(lit, steps: /* é𝒩 */ bands) * gain * grain.r), 1.0)\n}\n\
pass final: image(shade) {\n  out c: rgba8unorm = shade.color\n}\noutput final.c\n";

/// A directory of its own per test (they run in parallel), with a space
/// and an accent in its name.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("lsp")
        .join(test)
        .join("styles café");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::write(dir.join("lib.npr"), LIB).expect("write lib");
    std::fs::write(dir.join("main.npr"), MAIN).expect("write main");
    dir
}

fn open(client: &mut Client, doc: &str, language: &str, text: &str) {
    client.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": doc, "languageId": language, "version": 1, "text": text}}),
    );
}

fn started(dir: &Path) -> (Client, String) {
    let mut client = Client::start();
    let init = client.request(
        "initialize",
        json!({"processId": null, "rootUri": uri(dir), "capabilities": {}}),
    );
    let caps = &init["capabilities"];
    assert_eq!(caps["hoverProvider"], true, "{init}");
    assert_eq!(caps["definitionProvider"], true, "{init}");
    assert_eq!(caps["documentSymbolProvider"], true, "{init}");
    assert_eq!(caps["textDocumentSync"], 1, "full sync: {init}");
    client.notify("initialized", json!({}));
    let doc = uri(&dir.join("main.npr"));
    open(&mut client, &doc, "npr", MAIN);
    (client, doc)
}

fn hover_text(client: &mut Client, params: Value) -> String {
    let r = client.request("textDocument/hover", params);
    r["contents"]["value"]
        .as_str()
        .unwrap_or_else(|| panic!("a hover: {r}"))
        .to_string()
}

fn labels(result: &Value) -> Vec<String> {
    result
        .as_array()
        .expect("an array of items")
        .iter()
        .map(|i| i["label"].as_str().expect("label").to_string())
        .collect()
}

#[test]
fn diagnostics_on_open_and_change_with_utf16_ranges() {
    let dir = scratch("diagnostics_on_open_and_change_with_utf16_ranges");
    let (mut client, doc) = started(&dir);
    assert_eq!(client.diagnostics(&doc), Vec::<Value>::new(), "the style compiles");
    // A misspelt name after `é𝒩` on its line: the range counts UTF-16 units.
    let broken = MAIN.replace("*/ bands)", "*/ bnads)");
    client.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": doc, "version": 2}, "contentChanges": [{"text": broken}]}),
    );
    let diags = client.diagnostics(&doc);
    assert_eq!(diags.len(), 1, "{diags:?}");
    let d = &diags[0];
    assert_eq!(d["code"], "E0101", "{d}");
    assert_eq!(d["severity"], 1, "an error: {d}");
    assert_eq!(d["source"], "npr");
    let message = d["message"].as_str().expect("message");
    assert!(message.contains("unknown name `bnads`"), "{message}");
    assert!(message.contains("help: did you mean `bands`?"), "{message}");
    let start = pos(&broken, "bnads", 0, 0);
    assert_eq!(d["range"]["start"], start, "{d}");
    assert_eq!(
        d["range"]["end"]["character"],
        start["character"].as_u64().expect("col") + 5
    );
    // Byte columns would be larger: `é` is 2 bytes and `𝒩` 4 for 1 and 2 units.
    let line = broken.lines().find(|l| l.contains("bnads")).expect("the line");
    assert!(line.find("bnads").expect("bnads") > start["character"].as_u64().expect("col") as usize);
    // A warning keeps its severity and code; closing clears the document.
    let warned = MAIN.replace(
        "output final.c",
        "pass sums: compute(vertices) {\n  reduce n: float = sum(1.0)\n}\noutput final.c",
    );
    client.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": doc, "version": 3}, "contentChanges": [{"text": warned}]}),
    );
    let diags = client.diagnostics(&doc);
    assert_eq!(diags.len(), 1, "{diags:?}");
    assert_eq!(
        (diags[0]["code"].clone(), diags[0]["severity"].clone()),
        (json!("W0301"), json!(2))
    );
    // An error in the `use`d file: shown at the document's start, naming
    // the file, with the place itself as related information.
    std::fs::write(dir.join("lib.npr"), LIB.replace("1.0 in 0..2", "3m in 0..2")).expect("write lib");
    client.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": doc, "version": 4}, "contentChanges": [{"text": MAIN}]}),
    );
    let diags = client.diagnostics(&doc);
    assert!(!diags.is_empty(), "the used file's error is reported");
    let d = &diags[0];
    assert_eq!(d["range"]["start"], json!({"line": 0, "character": 0}), "{d}");
    assert!(d["message"].as_str().expect("message").contains("lib.npr:3:"), "{d}");
    let related = &d["relatedInformation"][0]["location"];
    assert_eq!(related["uri"], uri(&dir.join("lib.npr")).as_str(), "{d}");
    assert_eq!(related["range"]["start"]["line"], 2, "{d}");
    // A texture file that is not an image, as `npr check` reports it: at
    // the path in `image("…")`, after a non-ASCII name on the line.
    std::fs::write(dir.join("lib.npr"), LIB).expect("write lib");
    std::fs::write(dir.join("papér.png"), "not a png").expect("write");
    let textured = MAIN.replace("noise(size: 64)", "image(\"papér.png\", srgb)");
    client.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": doc, "version": 5}, "contentChanges": [{"text": textured}]}),
    );
    let diags = client.diagnostics(&doc);
    assert_eq!(diags.len(), 1, "{diags:?}");
    assert_eq!(diags[0]["code"], "E0401", "{diags:?}");
    assert_eq!(
        diags[0]["range"]["start"],
        pos(&textured, "\"papér.png\"", 0, 0),
        "{diags:?}"
    );
    assert_eq!(
        diags[0]["range"]["end"],
        pos(&textured, "\"papér.png\"", 0, 12),
        "{diags:?}"
    );
    client.notify("textDocument/didClose", json!({"textDocument": {"uri": doc}}));
    assert_eq!(client.diagnostics(&doc), Vec::<Value>::new());
}

#[test]
fn hover_shows_operators_params_builtins_passes_and_targets() {
    let dir = scratch("hover_shows_operators_params_builtins_passes_and_targets");
    let (mut client, doc) = started(&dir);
    let op = hover_text(&mut client, at(&doc, MAIN, "toon(", 0, 1));
    assert!(op.contains("toon(x: float, steps: int = 3 in 1..16) -> float"), "{op}");
    assert!(op.contains("Lake et al."), "the paper: {op}");
    assert!(
        op.contains("| `steps` | int | — | 3 | 1..16 | number of bands |"),
        "{op}"
    );
    let param = hover_text(&mut client, at(&doc, MAIN, "bands)", 0, 2));
    assert!(param.contains("param bands: int = 3 in 1..8"), "{param}");
    assert!(
        param.contains("Nombre de bandes — «bands» 𝒩."),
        "the doc comment: {param}"
    );
    let used = hover_text(&mut client, at(&doc, MAIN, "gain *", 0, 0));
    assert!(
        used.contains("param gain: float = 1.0 in 0..2") && used.contains("Overall gain."),
        "{used}"
    );
    let texture = hover_text(&mut client, at(&doc, MAIN, "grain.r", 0, 1));
    assert!(
        texture.contains("texture grain = noise(size: 64)") && texture.contains("Paper grain."),
        "{texture}"
    );
    let arg = hover_text(&mut client, at(&doc, MAIN, "steps:", 0, 1));
    assert!(
        arg.contains("number of bands") && arg.contains("range: 1..16") && arg.contains("parameter of `toon`"),
        "{arg}"
    );
    let builtin = hover_text(&mut client, at(&doc, MAIN, "light.dir", 0, 7));
    assert!(builtin.contains("light.dir: vec3"), "{builtin}");
    assert!(builtin.contains("towards the scene's `[light]`"), "{builtin}");
    let base = hover_text(&mut client, at(&doc, MAIN, "light.dir", 0, 2));
    assert!(base.contains("light.dir: vec3"), "the base names the member: {base}");
    let unit = hover_text(&mut client, at(&doc, MAIN, "normal,", 0, 0));
    assert!(
        unit.contains("normal: vec3") && unit.contains("render passes"),
        "{unit}"
    );
    let pass = hover_text(&mut client, at(&doc, MAIN, "shade.color", 0, 1));
    assert!(
        pass.contains("pass shade: render(scene)") && pass.contains("`out color: rgba8unorm`"),
        "{pass}"
    );
    let target = hover_text(&mut client, at(&doc, MAIN, "shade.color", 0, 8));
    assert!(
        target.contains("out color: rgba8unorm") && target.contains("of pass `shade`"),
        "{target}"
    );
    let kind = hover_text(&mut client, at(&doc, MAIN, "image(shade)", 0, 1));
    assert!(kind.contains("fullscreen pass"), "{kind}");
    let format = hover_text(&mut client, at(&doc, MAIN, "rgba8unorm", 0, 3));
    assert!(format.contains("4 channel(s)"), "{format}");
    let intrinsic = hover_text(&mut client, at(&doc, MAIN, "vec4(", 0, 1));
    assert!(intrinsic.contains("a 4-vector from scalars and vectors"), "{intrinsic}");
    // Nothing to say about a number or whitespace.
    let none = client.request("textDocument/hover", at(&doc, MAIN, "1..8", 0, 0));
    assert_eq!(none, Value::Null);
}

#[test]
fn completion_of_targets_formats_named_arguments_and_names() {
    let dir = scratch("completion_of_targets_formats_named_arguments_and_names");
    let (mut client, doc) = started(&dir);
    let targets = labels(&client.request("textDocument/completion", at(&doc, MAIN, "shade.color", 0, 6)));
    assert_eq!(targets, ["color"], "`shade.` → its targets");
    let members = labels(&client.request("textDocument/completion", at(&doc, MAIN, "light.dir", 0, 6)));
    assert!(
        members.contains(&"dir".to_string()) && members.contains(&"color".to_string()),
        "{members:?}"
    );
    let formats = labels(&client.request("textDocument/completion", at(&doc, MAIN, "out c: ", 0, 7)));
    for f in ["rgba8unorm", "r32float", "rg16float"] {
        assert!(formats.contains(&f.to_string()), "{f} in {formats:?}");
    }
    let args = client.request("textDocument/completion", at(&doc, MAIN, "toon(", 0, 5));
    let first = &args.as_array().expect("items")[0];
    assert_eq!(first["label"], "x");
    let names = labels(&args);
    assert!(
        names.contains(&"steps".to_string()),
        "named arguments of toon: {names:?}"
    );
    let steps = args
        .as_array()
        .expect("items")
        .iter()
        .find(|i| i["label"] == "steps")
        .expect("steps");
    assert_eq!(steps["insertText"], "steps: ");
    for name in [
        "lambert",
        "metatexture",
        "mix",
        "bands",
        "gain",
        "shade",
        "lit",
        "uv",
        "light",
        "time",
    ] {
        assert!(names.contains(&name.to_string()), "{name} in {names:?}");
    }
}

#[test]
fn definition_across_use_and_document_symbols() {
    let dir = scratch("definition_across_use_and_document_symbols");
    let (mut client, doc) = started(&dir);
    let lib = uri(&dir.join("lib.npr"));
    let gain = client.request("textDocument/definition", at(&doc, MAIN, "gain *", 0, 1));
    assert_eq!(gain["uri"], lib.as_str(), "{gain}");
    assert_eq!(gain["range"]["start"], json!({"line": 2, "character": 6}), "{gain}");
    let bands = client.request("textDocument/definition", at(&doc, MAIN, "bands)", 0, 0));
    assert_eq!(bands["uri"], doc.as_str());
    assert_eq!(bands["range"]["start"], pos(MAIN, "bands: int", 0, 0));
    let texture = client.request("textDocument/definition", at(&doc, MAIN, "grain.r", 0, 2));
    assert_eq!(texture["range"]["start"], pos(MAIN, "grain = noise", 0, 0));
    let pass = client.request("textDocument/definition", at(&doc, MAIN, "image(shade)", 0, 7));
    assert_eq!(pass["range"]["start"], pos(MAIN, "shade: render", 0, 0));
    let target = client.request("textDocument/definition", at(&doc, MAIN, "shade.color", 0, 8));
    assert_eq!(target["range"]["start"], pos(MAIN, "color: rgba8unorm", 0, 0));
    let output = client.request("textDocument/definition", at(&doc, MAIN, "final.c\n", 0, 6));
    assert_eq!(output["range"]["start"], pos(MAIN, "c: rgba8unorm", 0, 0));
    let local = client.request("textDocument/definition", at(&doc, MAIN, "lit,", 0, 1));
    assert_eq!(local["range"]["start"], pos(MAIN, "lit =", 0, 0));
    let operator = client.request("textDocument/definition", at(&doc, MAIN, "toon(", 0, 1));
    assert_eq!(operator, Value::Null, "a stdlib operator has no source to go to");

    let symbols = client.request("textDocument/documentSymbol", json!({"textDocument": {"uri": doc}}));
    let names: Vec<&str> = symbols
        .as_array()
        .expect("symbols")
        .iter()
        .map(|s| s["name"].as_str().expect("name"))
        .collect();
    assert_eq!(names, ["bands", "grain", "shade", "final", "output"], "{symbols}");
    let shade = &symbols[2];
    let children: Vec<&str> = shade["children"]
        .as_array()
        .expect("children")
        .iter()
        .map(|s| s["name"].as_str().expect("name"))
        .collect();
    assert_eq!(children, ["color", "lit"]);
    assert_eq!(shade["selectionRange"]["start"], pos(MAIN, "shade: render", 0, 0));
}

#[test]
fn bad_input_never_stops_the_server() {
    let dir = scratch("bad_input_never_stops_the_server");
    let (mut client, doc) = started(&dir);
    assert!(client.diagnostics(&doc).is_empty());
    // A frame whose body is not JSON: a parse error with a null id.
    client.send_raw(b"Content-Length: 9\r\n\r\n{not json");
    let err = client.wait(|m| m.get("error").is_some() && m["id"].is_null());
    assert_eq!(err["error"]["code"], -32700, "{err}");
    // JSON that is no JSON-RPC message, and a header line without CRLF.
    client.send_raw(b"Content-Length: 12\r\n\r\n{\"foo\": 12}\n");
    let err = client.wait(|m| m.get("error").is_some() && m["id"].is_null());
    assert_eq!(err["error"]["code"], -32700, "{err}");
    client.send_raw(b"garbage header\n");
    let err = client.wait(|m| m.get("error").is_some() && m["id"].is_null());
    assert_eq!(err["error"]["code"], -32700, "{err}");
    // Unknown methods: an error for a request, nothing for a notification.
    client.notify("$/noSuchNotification", json!({}));
    let unknown = client.request_full("npr/noSuchMethod", json!({}));
    assert_eq!(unknown["error"]["code"], -32601, "{unknown}");
    // Params of the wrong shape.
    let bad = client.request_full("textDocument/hover", json!({"textDocument": 3}));
    assert_eq!(bad["error"]["code"], -32602, "{bad}");
    // A document that is not `.npr`: no diagnostics, no answers about it.
    let notes = uri(&dir.join("notes.txt"));
    open(&mut client, &notes, "plaintext", "param x = (((\n");
    let hover = client.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": notes}, "position": {"line": 0, "character": 1}}),
    );
    assert_eq!(hover, Value::Null);
    assert!(
        !client
            .notifications
            .iter()
            .any(|n| n["params"]["uri"] == notes.as_str()),
        "diagnostics published for a text file: {:?}",
        client.notifications
    );
    // Positions past the end of the document, and an unopened document.
    let far = client.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": doc}, "position": {"line": 999, "character": 999}}),
    );
    assert_eq!(far, Value::Null);
    let unopened = uri(&dir.join("lib.npr"));
    let r = client.request("textDocument/completion", at(&unopened, LIB, "gain", 0, 0));
    assert_eq!(r, Value::Null);
    // Text that is not a style at all, and a didChange with no changes.
    client.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": doc, "version": 2}, "contentChanges": [{"text": "\u{0}\u{7f}{{{{ ((( é"}]}),
    );
    let diags = client.diagnostics(&doc);
    assert!(
        !diags.is_empty()
            && diags
                .iter()
                .all(|d| d["code"].as_str().is_some_and(|c| c.starts_with('E'))),
        "{diags:?}"
    );
    client.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": doc, "version": 3}, "contentChanges": []}),
    );
    // Still serving, and then a clean shutdown.
    let symbols = client.request("textDocument/documentSymbol", json!({"textDocument": {"uri": doc}}));
    assert!(symbols.is_array(), "{symbols}");
    assert_eq!(client.request("shutdown", Value::Null), Value::Null);
    client.notify("exit", Value::Null);
    let status = client.child.wait().expect("the server exits");
    assert_eq!(status.code(), Some(0));
}

#[test]
fn requests_before_initialize_are_refused_not_fatal() {
    let mut client = Client::start();
    let early = client.request_full("textDocument/hover", json!({}));
    assert_eq!(early["error"]["code"], -32002, "{early}");
    let init = client.request("initialize", json!({"processId": null, "capabilities": {}}));
    assert_eq!(init["serverInfo"]["name"], "npr");
    // End of input without shutdown: exit code 1, as the protocol says.
    client.stdin = None;
    let status = client.child.wait().expect("the server exits");
    assert_eq!(status.code(), Some(1));
}

/// A style's `.tests.toml`: the diagnostics `npr test` gives, at their
/// places in the buffer: E0407 for the file's own mistakes, and the
/// parameter values typed against the style (E0101, E0203). No hover or
/// symbols are offered for it.
#[test]
fn a_test_file_gets_the_diagnostics_npr_test_gives() {
    let dir = scratch("a_test_file_gets_the_diagnostics_npr_test_gives");
    std::fs::write(
        dir.join("scene.toml"),
        "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n",
    )
    .expect("scene");
    let (mut client, doc) = started(&dir);
    assert!(client.diagnostics(&doc).is_empty());
    let tests_doc = uri(&dir.join("main.tests.toml"));
    let good = "[[test]]\nname = \"café\"\nscene = \"scene.toml\"\nset = { bands = 5 }\n";
    let good = good.replace("café", "cafe");
    open(&mut client, &tests_doc, "toml", &good);
    assert_eq!(client.diagnostics(&tests_doc), Vec::<Value>::new(), "a good test file");

    // A misspelt key and a missing scene: E0407 at each.
    let bad = "[[test]]\nname = \"a\"\nsceen = \"scene.toml\"\n\n[[test]]\nname = \"b\"\nscene = \"nowhere.toml\"\n";
    client.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": tests_doc, "version": 2}, "contentChanges": [{"text": bad}]}),
    );
    let diags = client.diagnostics(&tests_doc);
    let codes: Vec<&str> = diags.iter().map(|d| d["code"].as_str().expect("code")).collect();
    assert!(codes.iter().all(|c| *c == "E0407") && codes.len() >= 2, "{diags:?}");
    assert!(
        diags
            .iter()
            .any(|d| d["range"]["start"] == pos(bad, "\"nowhere.toml\"", 0, 0)),
        "{diags:?}"
    );
    // Values typed against the style: an unknown parameter in `set` and an
    // out-of-range one in a variant, each at its place.
    let typed = "[[test]]\nname = \"a\"\nscene = \"scene.toml\"\nset = { bnads = 5 }\nvariants = { one = { bands = 1 }, many = { bands = 80 } }\n";
    client.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": tests_doc, "version": 3}, "contentChanges": [{"text": typed}]}),
    );
    let diags = client.diagnostics(&tests_doc);
    let found: Vec<(&str, Value)> = diags
        .iter()
        .map(|d| (d["code"].as_str().expect("code"), d["range"]["start"].clone()))
        .collect();
    assert!(found.contains(&("E0101", pos(typed, "bnads", 0, 0))), "{diags:?}");
    assert!(found.contains(&("E0203", pos(typed, "80", 0, 0))), "{diags:?}");
    // No hover on a test file.
    let hover = client.request("textDocument/hover", at(&tests_doc, typed, "bands", 0, 0));
    assert_eq!(hover, Value::Null);
}

#[test]
fn hover_shows_a_gradient_and_ramp() {
    let dir = scratch("hover_shows_a_gradient_and_ramp");
    let (mut client, _) = started(&dir);
    let text = "style \"Ramp\"\n/// Shadow to light.\nparam shading: gradient = gradient(stop(0.0, #2a1f4a), stop(1.0, #fff0d0))\n\
                pass p: render(scene) {\n  out c: rgba8unorm = ramp(shading, lambert(normal, light.dir))\n}\noutput p.c\n";
    let doc = uri(&dir.join("ramp.npr"));
    open(&mut client, &doc, "npr", text);
    assert_eq!(
        client.diagnostics(&doc),
        Vec::<Value>::new(),
        "a gradient compiles cleanly"
    );
    let g = hover_text(&mut client, at(&doc, text, "shading,", 0, 1));
    assert!(
        g.contains("param shading: gradient = gradient(stop(0.0, #2a1f4a), stop(1.0, #fff0d0))")
            && g.contains("Shadow to light."),
        "{g}"
    );
    let ramp = hover_text(&mut client, at(&doc, text, "ramp(", 0, 1));
    assert!(ramp.contains("gradient"), "{ramp}");
}
