//! The compiler in WebAssembly (issue 50, its first step), in a real
//! browser: `web/build.sh` builds the npr-web package (the compiler for
//! wasm32-unknown-unknown, bound by wasm-bindgen), a local server gives it
//! and the examples to Debian's headless Chromium, and the page
//! (`tests/data/web_package.js`) compiles every example style. Each WGSL
//! module and the manifest must equal, byte for byte, what `npr compile`
//! writes for the same style natively. A broken style must come back as an
//! `NprError` value carrying the code, line and column the command line
//! reports, never as a trap; a panic inside npr as an `NprError` E9001,
//! after which the module compiles again; `setParam` types values as
//! `--set` does.
//!
//! It also prints the package's size (raw and gzip) and the in-page
//! compile time against the native one for a few styles, measured in this
//! run (docs/PERFORMANCE.md records them; nothing here asserts a time).
//! Chromium or wasm-bindgen missing is a failure with the install command,
//! never a skip.

use crate::common;

use common::chromium::Browser;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// The example styles compiled in the page: the styles of `examples/` and
/// `examples/post/` (art-maps' filter styles are compiled as part of the
/// styles that name them), relative to `examples/`.
fn example_styles() -> Vec<String> {
    let root = common::root().join("examples");
    let mut names = Vec::new();
    for dir in ["", "post"] {
        for entry in std::fs::read_dir(root.join(dir)).expect("examples/") {
            let path = entry.expect("an entry").path();
            if path.extension().is_some_and(|e| e == "npr") {
                names.push(path.strip_prefix(&root).expect("inside").display().to_string());
            }
        }
    }
    names.sort();
    assert!(names.len() >= 20, "the examples went missing: {names:?}");
    names
}

/// The files the example styles may name (libraries, filters, textures),
/// relative to `examples/`: what the page is given with each style.
fn example_files() -> Vec<String> {
    let root = common::root().join("examples");
    let mut files = Vec::new();
    for dir in ["lib", "filters", "textures"] {
        for entry in std::fs::read_dir(root.join(dir)).expect("an examples folder") {
            let path = entry.expect("an entry").path();
            if path.is_file() {
                files.push(path.strip_prefix(&root).expect("inside").display().to_string());
            }
        }
    }
    files.sort();
    files
}

/// `web/build.sh` into `out`: the package the page imports.
fn build_package(out: &Path) {
    let status = Command::new("bash")
        .arg(common::root().join("web/build.sh"))
        .arg(out)
        .current_dir(common::root())
        .status()
        .expect("run web/build.sh");
    assert!(
        status.success(),
        "web/build.sh failed (it needs the wasm32 target and wasm-bindgen-cli: `./setup.sh --tests` installs both)"
    );
    for file in ["npr.js", "npr_web.js", "npr_web_bg.wasm", "npr_web.d.ts"] {
        assert!(out.join(file).is_file(), "web/build.sh wrote no {file}");
    }
}

/// `npr compile NAME -o OUT` in `examples/`: the native output the page's must equal.
fn native_compile(name: &str, out: &Path) {
    let run = Command::new(env!("CARGO_BIN_EXE_npr"))
        .current_dir(common::root().join("examples"))
        .args(["compile", name, "-o"])
        .arg(out)
        .output()
        .expect("npr runs");
    assert!(
        run.status.success(),
        "npr compile {name}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
}

/// A server on 127.0.0.1 (a secure context) for `/pkg/` (the package) and
/// `/examples/`; every other path is an empty page.
fn serve(package: PathBuf) -> String {
    let server = tiny_http::Server::http("127.0.0.1:0").expect("a local port");
    let addr = server.server_addr().to_ip().expect("an IP address").to_string();
    let examples = common::root().join("examples");
    std::thread::spawn(move || {
        for request in server.incoming_requests() {
            let url = request.url().split('?').next().unwrap_or("").to_string();
            let file = url
                .strip_prefix("/pkg/")
                .map(|f| package.join(f))
                .or_else(|| url.strip_prefix("/examples/").map(|f| examples.join(f)));
            let header = |ty: &str| tiny_http::Header::from_bytes("Content-Type", ty).expect("a header");
            let response = match file {
                // No `..` in a test's own URLs; refuse any all the same.
                Some(path) if !url.contains("..") => match std::fs::read(&path) {
                    Ok(bytes) => {
                        let ty = match path.extension().and_then(|e| e.to_str()) {
                            Some("js") => "text/javascript",
                            Some("wasm") => "application/wasm",
                            _ => "application/octet-stream",
                        };
                        tiny_http::Response::from_data(bytes).with_header(header(ty))
                    }
                    Err(_) => tiny_http::Response::from_data(Vec::new()).with_status_code(404),
                },
                Some(_) => tiny_http::Response::from_data(Vec::new()).with_status_code(403),
                None => tiny_http::Response::from_data(b"<!doctype html><title>npr-web test</title>".to_vec())
                    .with_header(header("text/html")),
            };
            let _ = request.respond(response);
        }
    });
    addr
}

/// The page, with the package loaded and the example files fetched.
fn page(addr: &str, scratch: &Path) -> Browser {
    let mut b = Browser::launch(&scratch.join("profile"), &[], Duration::from_secs(120));
    b.call("Page.enable", json!({}));
    b.call("Page.navigate", json!({"url": format!("http://{addr}/")}));
    let deadline = Instant::now() + common::live::HANG;
    while b.eval("document.readyState === 'complete' && location.protocol === 'http:'") != json!(true) {
        assert!(Instant::now() < deadline, "the test page never loaded");
        std::thread::sleep(Duration::from_millis(50));
    }
    assert_eq!(b.eval(include_str!("../data/web_package.js")), json!("ready"));
    let files = example_files();
    let loaded = b.eval(&format!("nprWeb.loadFiles({})", json!(files)));
    assert_eq!(loaded, json!(files.len()), "the page fetched the example files");
    b
}

/// What the page compiled, against `npr compile`'s directory `native`.
fn compare(name: &str, page: &Value, native: &Path) -> Vec<String> {
    let mut problems = Vec::new();
    if page["ok"] != json!(true) {
        return vec![format!("{name}: the page did not compile it: {}", page["error"])];
    }
    let mut expected: Vec<String> = std::fs::read_dir(native)
        .expect("npr compile's output")
        .map(|e| e.expect("an entry").file_name().to_string_lossy().into_owned())
        .filter(|f| f.ends_with(".wgsl"))
        .collect();
    expected.sort();
    let modules = page["modules"].as_array().expect("modules");
    let mut got: Vec<String> = modules
        .iter()
        .map(|m| m[0].as_str().unwrap_or("").to_string())
        .collect();
    got.sort();
    if got != expected {
        problems.push(format!(
            "{name}: the page's modules {got:?}, npr compile's {expected:?}"
        ));
    }
    for m in modules {
        let file = m[0].as_str().unwrap_or("");
        let native_wgsl = std::fs::read_to_string(native.join(file)).unwrap_or_default();
        if m[1].as_str() != Some(native_wgsl.as_str()) {
            problems.push(format!("{name}: {file} differs from npr compile's"));
        }
    }
    let manifest = std::fs::read_to_string(native.join("manifest.json")).expect("manifest.json");
    if page["manifest"].as_str() != Some(manifest.as_str()) {
        problems.push(format!("{name}: manifest.json differs from npr compile's"));
    }
    problems
}

/// The native compile time of `name` in milliseconds, over `runs`
/// compiles after one to warm up: the same in-memory files as the page's.
fn native_compile_ms(name: &str, runs: u32) -> f64 {
    let root = common::root().join("examples");
    let source = std::fs::read_to_string(root.join(name)).expect("the example");
    let request = npr_web::compile::Request {
        name: name.to_string(),
        source,
        files: example_files()
            .into_iter()
            .map(|f| {
                let bytes = std::fs::read(root.join(&f)).expect("an example file");
                (f, bytes)
            })
            .collect(),
        keep_params: false,
    };
    npr_web::compile::compile(&request).expect("compiles natively");
    let start = Instant::now();
    for _ in 0..runs {
        npr_web::compile::compile(&request).expect("compiles natively");
    }
    start.elapsed().as_secs_f64() * 1e3 / f64::from(runs)
}

fn gzip_size(bytes: &[u8]) -> usize {
    use std::io::Write;
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    gz.write_all(bytes).expect("gzip");
    gz.finish().expect("gzip").len()
}

#[test]
fn the_compiler_in_the_browser_gives_what_npr_compile_gives() {
    let scratch = common::live::scratch("web-package", "run");
    let package = scratch.join("pkg");
    build_package(&package);
    let addr = serve(package.clone());
    let mut b = page(&addr, &scratch);

    // 1. Every example, byte for byte.
    let mut problems = Vec::new();
    let styles = example_styles();
    for name in &styles {
        let native = scratch.join("native").join(name.replace('/', "_"));
        native_compile(name, &native);
        let got = b.eval(&format!("nprWeb.compileExample({})", json!(name)));
        problems.extend(compare(name, &got, &native));
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));

    // 2. A broken style: an NprError value with the code, line and column
    // the command line gives for the same text.
    let broken = "style \"Broken\"\nparam bands: int = 3\npass final: image() {\n  out color: rgba8unorm = vec4(band, 0.0, 0.0, 1.0)\n}\n";
    let file = scratch.join("broken.npr");
    std::fs::write(&file, broken).expect("write the broken style");
    let cli = Command::new(env!("CARGO_BIN_EXE_npr"))
        .args(["compile", "broken.npr", "-o", "out", "--message-format", "json"])
        .current_dir(&scratch)
        .output()
        .expect("npr runs");
    assert_eq!(cli.status.code(), Some(1), "{}", String::from_utf8_lossy(&cli.stderr));
    let cli_json: Value = String::from_utf8_lossy(&cli.stdout)
        .lines()
        .chain(String::from_utf8_lossy(&cli.stderr).lines())
        .find_map(|l| serde_json::from_str(l).ok())
        .expect("a JSON diagnostic from npr compile");
    let label = &cli_json["labels"][0];
    let got = b.eval(&format!("nprWeb.compile('broken.npr', {})", json!(broken)));
    let error = &got["error"];
    assert_eq!(got["ok"], json!(false), "{got}");
    assert_eq!(error["isNprError"], json!(true), "not an NprError: {error}");
    assert_eq!(error["isTrap"], json!(false), "a trap: {error}");
    assert_eq!(error["code"], cli_json["code"], "{error}");
    assert_eq!(error["code"], json!("E0101"), "{error}");
    assert_eq!((&error["line"], &error["column"]), (&json!(4), &json!(32)), "{error}");
    assert_eq!(
        (&error["line"], &error["column"]),
        (&label["line"], &label["column"]),
        "{error}"
    );
    assert_eq!(error["file"], json!("broken.npr"), "{error}");
    assert!(
        error["message"]
            .as_str()
            .is_some_and(|m| m.contains("E0101") && m.contains("band")),
        "{error}"
    );
    assert_eq!(error["diagnostics"][0]["rendered"], cli_json["rendered"], "{error}");

    // 3. Files outside the style's directory are refused as on disk.
    // (In memory the root is the directory the files are named from.)
    let outside = "style \"Outside\"\nuse \"../examples/lib/dynamic_pattern.npr\"\n";
    let got = b.eval(&format!("nprWeb.compile('outside.npr', {})", json!(outside)));
    assert_eq!(got["error"]["code"], json!("E0406"), "{got}");
    assert_eq!(
        (&got["error"]["line"], &got["error"]["file"]),
        (&json!(2), &json!("outside.npr")),
        "{got}"
    );

    // 4. A panic inside npr: an NprError E9001, and the module works after it.
    let got = b.eval("nprWeb.panicThenCompile('toon.npr')");
    let seen = &got["seen"];
    assert_eq!(seen["threw"], json!(true), "{got}");
    assert_eq!(
        (&seen["isNprError"], &seen["isTrap"]),
        (&json!(true), &json!(false)),
        "{got}"
    );
    assert_eq!(seen["code"], json!("E9001"), "{got}");
    assert!(
        seen["message"].as_str().is_some_and(|m| m.contains("deliberate panic")),
        "{got}"
    );
    assert_eq!(got["after"]["ok"], json!(true), "no compile after the panic: {got}");

    // 5. setParam: typed as `--set` types it, refusals as values.
    let got = b.eval("nprWeb.setParams('toon.npr', 'bands', [5, '6', 'seven', 40])");
    let default = |i: usize| got[i]["default"][0].as_f64();
    assert_eq!((default(0), default(1)), (Some(5.0), Some(6.0)), "{got}");
    assert_eq!(got[2]["error"]["code"], json!("E0201"), "{got}");
    assert_eq!(got[3]["error"]["code"], json!("E0203"), "{got}");
    let got = b.eval("nprWeb.setParams('toon.npr', 'bandz', [5])");
    assert_eq!(got[0]["error"]["code"], json!("E0101"), "{got}");
    assert!(
        got[0]["error"]["message"].as_str().is_some_and(|m| m.contains("bands")),
        "{got}"
    );

    // Figures for docs/PERFORMANCE.md, measured in this run; not asserted.
    let wasm = std::fs::read(package.join("npr_web_bg.wasm")).expect("the package's wasm");
    eprintln!(
        "web_package: npr_web_bg.wasm {} bytes, {} gzip (-9)",
        wasm.len(),
        gzip_size(&wasm)
    );
    for name in ["toon.npr", "age_of_sail.npr", "artmap_gallery.npr", "lsa_contours.npr"] {
        let runs = 10;
        let page_ms = b.eval(&format!("nprWeb.timeExample({}, {runs})", json!(name)));
        let page_ms = page_ms.as_f64().expect("milliseconds");
        let native_ms = native_compile_ms(name, runs);
        eprintln!(
            "web_package: {name}: {page_ms:.1} ms in the page, {native_ms:.1} ms native ({:.2}x)",
            page_ms / native_ms
        );
    }
}
