//! The JavaScript API (wasm-bindgen): `Style.compile(source, files?,
//! options?)`, its WGSL modules and manifest, `setParam`, and the errors.
//!
//! An error reaches JavaScript as a thrown `NprError` value: an `Error`
//! whose `message` is the first error rendered as on the command line,
//! with `code`, `file`, `line` and `column` of that error's primary label
//! and every diagnostic in `diagnostics`. A panic inside npr cannot be
//! caught in WebAssembly (panics abort there), so the hook installed at
//! start leaves its message where `js/npr.js` finds it after the trap
//! (`globalThis[Symbol.for("npr.panic")]`), and that turns the trap into an
//! `NprError` with code E9001.

use crate::compile::{self, Failure, Request};
use wasm_bindgen::prelude::*;

#[wasm_bindgen(typescript_custom_section)]
const TS_TYPES: &str = r#"
/** The files a style names (`use`, art-map filters, `image("…")`), each
 * relative to the style's directory: text or bytes. */
export type NprFiles = Record<string, string | Uint8Array>;

/** How to compile: the style's file name (default `style.npr`) and
 * whether its parameters stay live for `setParam`. */
export interface NprCompileOptions { name?: string; keepParams?: boolean; }

/** One label of a diagnostic, with its 1-based line and column. */
export interface NprLabel { file: string; byte_start: number; byte_end: number; line: number; column: number; message: string; primary: boolean; }

/** A diagnostic, as `npr --message-format json` writes it. */
export interface NprDiagnostic { severity: "error" | "warning" | "note"; code: string; message: string; help: string | null; notes: string[]; labels: NprLabel[]; rendered: string; }

/** What `Style.compile` and `setParam` throw. */
export interface NprError extends Error { name: "NprError"; code: string; file: string | null; line: number | null; column: number | null; diagnostics: NprDiagnostic[]; }
"#;

#[wasm_bindgen]
extern "C" {
    #[wasm_bindgen(typescript_type = "NprFiles")]
    pub type JsFiles;
    #[wasm_bindgen(typescript_type = "NprCompileOptions")]
    pub type JsCompileOptions;
    #[wasm_bindgen(typescript_type = "NprDiagnostic[]")]
    pub type JsDiagnostics;
    #[wasm_bindgen(typescript_type = "string | number | boolean")]
    pub type JsParamValue;
}

#[wasm_bindgen(
    inline_js = "export function npr_record_panic(message) { globalThis[Symbol.for('npr.panic')] = message; }"
)]
extern "C" {
    fn npr_record_panic(message: &str);
}

/// Runs when the module is instantiated: every panic leaves its message
/// for `npr.js` before the trap.
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        npr_record_panic(&info.to_string());
    }));
}

/// A compiled style: its WGSL modules and manifest.
#[wasm_bindgen]
pub struct Style {
    output: compile::Output,
    name: String,
}

/// One pass's WGSL module.
#[wasm_bindgen]
pub struct ShaderModule {
    file: String,
    wgsl: String,
}

#[wasm_bindgen]
impl ShaderModule {
    /// The shader's file name, as `npr compile -o DIR` writes it (`<pass>.wgsl`).
    #[wasm_bindgen(getter)]
    pub fn file(&self) -> String {
        self.file.clone()
    }

    #[wasm_bindgen(getter)]
    pub fn wgsl(&self) -> String {
        self.wgsl.clone()
    }
}

#[wasm_bindgen]
impl Style {
    /// Compile `source`; the files it names come from `files` alone.
    /// Throws an `NprError` when the style does not compile.
    pub fn compile(source: &str, files: Option<JsFiles>, options: Option<JsCompileOptions>) -> Result<Style, JsValue> {
        let options: JsValue = options.map(Into::into).unwrap_or(JsValue::UNDEFINED);
        let name = field(&options, "name")
            .as_string()
            .unwrap_or_else(|| compile::DEFAULT_NAME.to_string());
        let keep_params = field(&options, "keepParams").as_bool().unwrap_or(false);
        let files = match files {
            Some(f) => read_files(&f.into())?,
            None => Vec::new(),
        };
        let request = Request {
            name: name.clone(),
            source: source.to_string(),
            files,
            keep_params,
        };
        let output = compile::compile(&request).map_err(|f| error_value(&f))?;
        Ok(Style { output, name })
    }

    /// The style's file name.
    #[wasm_bindgen(getter)]
    pub fn name(&self) -> String {
        self.name.clone()
    }

    /// Each live pass's WGSL, in execution order.
    #[wasm_bindgen(getter)]
    pub fn modules(&self) -> Vec<ShaderModule> {
        self.output
            .shaders
            .iter()
            .map(|(file, wgsl)| ShaderModule {
                file: file.clone(),
                wgsl: wgsl.clone(),
            })
            .collect()
    }

    /// The manifest, as `npr compile -o DIR` writes `manifest.json`
    /// (with the values `setParam` gave).
    #[wasm_bindgen(getter, js_name = manifestJson)]
    pub fn manifest_json(&self) -> String {
        self.output.manifest_json()
    }

    /// The warnings the compile gave.
    #[wasm_bindgen(getter)]
    pub fn warnings(&self) -> JsDiagnostics {
        json_array(&self.output.warnings).unchecked_into()
    }

    /// Set a live parameter (the style compiled with `keepParams`) to
    /// `value`, written as `npr --set` takes it (`5`, `"2px"`, `"#ff8800"`,
    /// `true`). Throws an `NprError` and changes nothing when it is refused.
    #[wasm_bindgen(js_name = setParam)]
    pub fn set_param(&mut self, name: &str, value: JsParamValue) -> Result<(), JsValue> {
        let value: JsValue = value.into();
        let written = if let Some(s) = value.as_string() {
            s
        } else if let Some(n) = value.as_f64() {
            format!("{n}")
        } else if let Some(b) = value.as_bool() {
            b.to_string()
        } else {
            return Err(error_value(&Failure::of(
                npr_diag::Diagnostic::error(
                    npr_diag::codes::BAD_ARGUMENT_VALUE,
                    format!("setParam(\"{name}\"): the value is not a string, number or boolean"),
                )
                .with_help("write the value as `npr --set` takes it: 5, \"2px\", \"#ff8800\", true"),
            )));
        };
        crate::params::set_param(&mut self.output.manifest.params, name, &written)
            .map_err(|d| error_value(&Failure::of(d)))
    }
}

/// A hidden export for the browser test of `npr.js`'s trap handling: it
/// panics, as a bug in npr would.
#[doc(hidden)]
#[wasm_bindgen(js_name = "__nprPanicForTests", skip_typescript)]
pub fn panic_for_tests() {
    panic!("a deliberate panic (the test of npr.js's trap handling)");
}

/// `object[key]`, or `undefined`.
fn field(object: &JsValue, key: &str) -> JsValue {
    if !object.is_object() {
        return JsValue::UNDEFINED;
    }
    js_sys::Reflect::get(object, &JsValue::from_str(key)).unwrap_or(JsValue::UNDEFINED)
}

/// The `(path, bytes)` of a files object: each value a string (its UTF-8)
/// or a `Uint8Array`.
fn read_files(files: &JsValue) -> Result<Vec<(String, Vec<u8>)>, JsValue> {
    let refuse = |what: String| {
        error_value(&Failure::of(
            npr_diag::Diagnostic::error(npr_diag::codes::BAD_ARGUMENT_VALUE, what)
                .with_help("give the files as an object of paths to strings or Uint8Arrays"),
        ))
    };
    if !files.is_object() {
        return Err(refuse("the files given with the style are not an object".into()));
    }
    let mut out = Vec::new();
    for entry in js_sys::Object::entries(files.unchecked_ref()).iter() {
        let pair: js_sys::Array = entry.unchecked_into();
        let path = pair.get(0).as_string().unwrap_or_default();
        let value = pair.get(1);
        let bytes = if let Some(text) = value.as_string() {
            text.into_bytes()
        } else if let Some(array) = value.dyn_ref::<js_sys::Uint8Array>() {
            array.to_vec()
        } else {
            return Err(refuse(format!(
                "the file `{path}` is neither a string nor a Uint8Array"
            )));
        };
        out.push((path, bytes));
    }
    Ok(out)
}

/// `values` as a JavaScript array of objects.
fn json_array(values: &[serde_json::Value]) -> JsValue {
    let text = serde_json::Value::Array(values.to_vec()).to_string();
    js_sys::JSON::parse(&text).unwrap_or_else(|_| js_sys::Array::new().into())
}

/// The `NprError` of a failure: an `Error` carrying the first error's
/// code and place, and every diagnostic.
fn error_value(failure: &Failure) -> JsValue {
    let first = failure.first();
    let rendered = first["rendered"]
        .as_str()
        .or_else(|| first["message"].as_str())
        .unwrap_or("npr error");
    let error = js_sys::Error::new(rendered.trim_end());
    error.set_name("NprError");
    let primary = first["labels"]
        .as_array()
        .and_then(|labels| labels.iter().find(|l| l["primary"] == true));
    let place = |key: &str| primary.map(|l| l[key].clone()).unwrap_or(serde_json::Value::Null);
    let summary = serde_json::json!({
        "code": first["code"],
        "file": place("file"),
        "line": place("line"),
        "column": place("column"),
    });
    let fields = js_sys::JSON::parse(&summary.to_string()).unwrap_or(JsValue::NULL);
    if let Some(fields) = fields.dyn_ref::<js_sys::Object>() {
        js_sys::Object::assign(error.unchecked_ref(), fields);
    }
    let _ = js_sys::Reflect::set(
        &error,
        &JsValue::from_str("diagnostics"),
        &json_array(&failure.diagnostics),
    );
    error.into()
}
