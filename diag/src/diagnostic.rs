//! User-facing diagnostics: an error code, a primary span with a label, a help
//! line, rendered like rustc (codespan-reporting) or as JSON.
//!
//! Every stage of npr reports user errors through [`Diagnostic`]; the code
//! table in [`codes`] is the single list of error codes, and each one has a
//! snapshot test of its rendered message.

use crate::span::{SourceMap, Span};
use codespan_reporting::diagnostic as cs;
use codespan_reporting::files::SimpleFiles;
use codespan_reporting::term;
use serde::Serialize;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    Error,
    Warning,
    Note,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Label {
    pub span: Span,
    pub message: String,
    pub primary: bool,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Diagnostic {
    pub severity: Severity,
    /// A stable code from [`codes`], e.g. `E0101`.
    pub code: &'static str,
    pub message: String,
    pub labels: Vec<Label>,
    pub help: Option<String>,
    pub notes: Vec<String>,
}

impl Diagnostic {
    pub fn error(code: &'static str, message: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Error,
            code,
            message: message.into(),
            labels: Vec::new(),
            help: None,
            notes: Vec::new(),
        }
    }

    pub fn warning(code: &'static str, message: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(code, message)
        }
    }

    /// The primary label: where the problem is.
    pub fn with_primary(mut self, span: Span, label: impl Into<String>) -> Self {
        self.labels.push(Label {
            span,
            message: label.into(),
            primary: true,
        });
        self
    }

    /// A secondary label: related context.
    pub fn with_secondary(mut self, span: Span, label: impl Into<String>) -> Self {
        self.labels.push(Label {
            span,
            message: label.into(),
            primary: false,
        });
        self
    }

    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    pub fn primary_span(&self) -> Option<Span> {
        self.labels.iter().find(|l| l.primary).map(|l| l.span)
    }
}

/// Did you mean …? The closest candidate by Jaro-Winkler similarity, if close enough.
pub fn did_you_mean<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|c| (strsim::jaro_winkler(name, c), c))
        .filter(|(score, _)| *score > 0.8)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c)
}

/// Render diagnostics like rustc. `color` adds ANSI colours (for terminals).
pub fn render(diags: &[Diagnostic], sources: &SourceMap, color: bool) -> String {
    let mut files = SimpleFiles::new();
    for f in sources.files() {
        files.add(f.name.clone(), f.text.clone());
    }
    let config = term::Config::default();
    let mut out: Vec<u8> = Vec::new();
    for d in diags {
        let cs_diag = to_codespan(d);
        if color {
            let mut w = term::termcolor::Ansi::new(&mut out);
            let _ = term::emit_to_write_style(&mut w, &config, &files, &cs_diag);
        } else {
            let mut w = term::termcolor::NoColor::new(&mut out);
            let _ = term::emit_to_write_style(&mut w, &config, &files, &cs_diag);
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

fn to_codespan(d: &Diagnostic) -> cs::Diagnostic<usize> {
    let sev = match d.severity {
        Severity::Error => cs::Severity::Error,
        Severity::Warning => cs::Severity::Warning,
        Severity::Note => cs::Severity::Note,
    };
    let labels = d
        .labels
        .iter()
        .map(|l| {
            let style = if l.primary {
                cs::LabelStyle::Primary
            } else {
                cs::LabelStyle::Secondary
            };
            cs::Label::new(style, l.span.file.0 as usize, l.span.range()).with_message(&l.message)
        })
        .collect();
    let mut notes: Vec<String> = d.notes.clone();
    if let Some(h) = &d.help {
        notes.push(format!("help: {h}"));
    }
    cs::Diagnostic::new(sev)
        .with_code(d.code)
        .with_message(&d.message)
        .with_labels(labels)
        .with_notes(notes)
}

/// One diagnostic as JSON, with file names and 1-based line/column resolved.
#[derive(Debug, Serialize)]
pub struct JsonDiagnostic<'a> {
    pub severity: Severity,
    pub code: &'a str,
    pub message: &'a str,
    pub help: Option<&'a str>,
    pub notes: &'a [String],
    pub labels: Vec<JsonLabel<'a>>,
    pub rendered: String,
}

#[derive(Debug, Serialize)]
pub struct JsonLabel<'a> {
    pub file: String,
    pub byte_start: u32,
    pub byte_end: u32,
    pub line: usize,
    pub column: usize,
    pub message: &'a str,
    pub primary: bool,
}

/// Machine-readable diagnostics: one JSON object per line (like `cargo --message-format json`).
pub fn render_json(diags: &[Diagnostic], sources: &SourceMap) -> String {
    let mut out = String::new();
    for d in diags {
        let labels = d
            .labels
            .iter()
            .map(|l| {
                let (line, column) = sources.line_col(l.span.file, l.span.start);
                JsonLabel {
                    file: sources.get(l.span.file).map(|f| f.name.clone()).unwrap_or_default(),
                    byte_start: l.span.start,
                    byte_end: l.span.end,
                    line,
                    column,
                    message: &l.message,
                    primary: l.primary,
                }
            })
            .collect();
        let j = JsonDiagnostic {
            severity: d.severity,
            code: d.code,
            message: &d.message,
            help: d.help.as_deref(),
            notes: &d.notes,
            labels,
            rendered: render(std::slice::from_ref(d), sources, false),
        };
        out.push_str(&serde_json::to_string(&j).unwrap_or_default());
        out.push('\n');
    }
    out
}

/// The table of error codes. Each code has one meaning, forever.
pub mod codes {
    /// Syntax error: the text does not match the grammar.
    pub const SYNTAX: &str = "E0001";
    /// The style header `style "..."` is missing or repeated.
    pub const STYLE_HEADER: &str = "E0002";
    /// A name is declared twice.
    pub const DUPLICATE_NAME: &str = "E0003";
    /// `use` of a file that cannot be read, or a `use` cycle.
    pub const BAD_USE: &str = "E0004";
    /// Brackets, blocks, calls or `if`s nested past `limits::MAX_NESTING`.
    pub const NESTED_TOO_DEEP: &str = "E0005";
    /// An expression deeper than `limits::MAX_EXPR_DEPTH` (a long operator chain counts).
    pub const EXPRESSION_TOO_DEEP: &str = "E0006";
    /// A style or scene file that is not valid UTF-8 text.
    pub const NOT_UTF8: &str = "E0007";
    /// Unknown name (parameter, builtin, let, pass, texture).
    pub const UNKNOWN_NAME: &str = "E0101";
    /// Unknown operator or function.
    pub const UNKNOWN_OPERATOR: &str = "E0102";
    /// Unknown or misused argument name, or a missing required argument.
    pub const BAD_ARGUMENT: &str = "E0103";
    /// Unknown type, texture format, field or swizzle.
    pub const UNKNOWN_TYPE: &str = "E0104";
    /// Type mismatch.
    pub const TYPE_MISMATCH: &str = "E0201";
    /// Unit mismatch (e.g. px + m).
    pub const UNIT_MISMATCH: &str = "E0202";
    /// A literal, default or keyframe outside its declared range, or an empty range.
    pub const OUT_OF_RANGE: &str = "E0203";
    /// An expression that must be constant is not.
    pub const NOT_CONSTANT: &str = "E0204";
    /// A dependency cycle between passes.
    pub const PASS_CYCLE: &str = "E0301";
    /// A per-object value (`reduce`, `out` or `state` of a compute pass) of a type it cannot have.
    pub const BAD_VALUE_TYPE: &str = "E0205";
    /// A gradient with no stops, stops out of order, a position outside
    /// 0..1, or a stop that is not `stop(position, colour)`.
    pub const BAD_GRADIENT: &str = "E0206";
    /// Warning: a colour combined with a plain `vec4` whose alpha scales or
    /// shifts the colour's coverage (`c * vec4(k)`): an opaque colour may
    /// come out transparent (`compiler/src/front/typecheck/color.rs`).
    pub const COLOR_ALPHA_CHANGED: &str = "W0201";
    /// Warning (issue 49, `compiler/src/mid/ranges/`): `log` or `log2` of
    /// a value that the declared ranges let reach 0 or below.
    pub const LOG_DOMAIN: &str = "W0203";
    /// Warning: `sqrt` of a value that may be negative.
    pub const SQRT_DOMAIN: &str = "W0204";
    /// Warning: `pow(x, y)` with x possibly negative, or 0 with y ≤ 0.
    pub const POW_DOMAIN: &str = "W0205";
    /// Warning: a division (`/`, `%`, `smoothstep`'s edges) by a range holding 0.
    pub const DIVISION_BY_ZERO: &str = "W0206";
    /// Warning: `asin` or `acos` of a value that may leave [−1, 1].
    pub const INVERSE_TRIG_DOMAIN: &str = "W0207";
    /// Warning: `normalize` of a vector that may be zero.
    pub const NORMALIZE_ZERO: &str = "W0208";
    /// Warning: `atan2(y, x)` where both may be 0.
    pub const ATAN2_ORIGIN: &str = "W0209";
    /// Warning: a value stored into an f16 target that may pass 65504.
    pub const F16_OVERFLOW: &str = "W0210";
    /// A value written into a target of an incompatible format.
    pub const FORMAT_MISMATCH: &str = "E0302";
    /// No `output`, or an output that names no target.
    pub const NO_OUTPUT: &str = "E0303";
    /// A pass reads a target that is not listed in its inputs, or a render-only builtin in an image pass.
    pub const BAD_PASS_INPUT: &str = "E0304";
    /// A state read before it is declared, never updated, updated twice, or an assignment to a non-state.
    pub const STATE_ORDER: &str = "E0305";
    /// A statement the pass kind does not have (`reduce` in a render pass, `out` in `compute(vertices)`).
    pub const BAD_STATEMENT: &str = "E0306";
    /// Warning: a compute pass whose values no live pass reads (it is removed).
    pub const UNREAD_COMPUTE: &str = "W0301";
    /// Warning: a render pass reads `patch.weight` (it draws each patch over
    /// its n-ring, Breslav et al. 2007 §3.6) without a depth test against an
    /// earlier pass's kept depth, so the overlapping copies are not occluded.
    pub const PATCH_BLEND_UNOCCLUDED: &str = "W0302";
    /// A blend mode on an output whose format cannot be blended (32-bit float; integer formats, should they come).
    pub const NOT_BLENDABLE: &str = "E0307";
    /// A depth test against a pass that keeps no depth buffer.
    pub const DEPTH_NOT_KEPT: &str = "E0308";
    /// The target a `compute(pixels, ...)` pass runs over is not an ID target (`r32float`).
    pub const BAD_ID_TARGET: &str = "E0309";
    /// An art-map filter style that is not one (it must read one
    /// `filter_input()` and run image passes only), an art-map inside a
    /// filter, or a filter rendered on a scene.
    pub const BAD_FILTER: &str = "E0310";
    /// An image pass whose `schedule: tiled` the tiler refuses (it blends,
    /// writes a format compute cannot store, takes screen derivatives, reads
    /// nothing around the pixel, or its tiles do not fit in workgroup memory).
    pub const CANNOT_TILE: &str = "E0311";
    /// An image pass whose `schedule: recompute` cannot be done: its target
    /// is not read by one same-scale image pass around the pixel, or that
    /// reader cannot be tiled with it (`compiler/src/schedule/recompute.rs`).
    pub const CANNOT_RECOMPUTE: &str = "E0312";
    /// A line set's `edges:` names an edge type there is not (decision 0056),
    /// or is not a union of edge types.
    pub const UNKNOWN_EDGE_TYPE: &str = "E0313";
    /// A line set's `crease(angle)` without an angle in `deg` in 0..180.
    pub const BAD_CREASE_ANGLE: &str = "E0314";
    /// A line set that selects nothing: no `edges:`, or every edge it
    /// selects goes to a set of higher priority over the same objects.
    pub const EMPTY_LINE_SET: &str = "E0315";
    /// Two line sets of one pass with one name.
    pub const DUPLICATE_LINE_SET: &str = "E0316";
    /// A line set where there can be none: `set` outside a lines pass, the
    /// pass-level `silhouettes:`/`creases:` beside sets, a setting a set
    /// does not have, or `line.color`/`line.set` in a pass without sets.
    pub const MISPLACED_LINE_SET: &str = "E0317";
    /// A line set's `visibility:` other than `visible`, `hidden`,
    /// `hidden(n)` (n a whole number from 1) or `all`.
    pub const BAD_LINE_VISIBILITY: &str = "E0318";
    /// `depth: test(name)` where `name` is neither a pass nor an
    /// `input(depth)` texture (a colour input, a param).
    pub const NOT_A_TESTED_DEPTH: &str = "E0319";
    /// A pass that tests against the host's depth (`depth: test(input)`)
    /// at another scale than the output's, or through the light's view:
    /// the host's depth is the camera's, at the output's size.
    pub const INPUT_DEPTH_MISMATCH: &str = "E0320";
    /// `uv` in an image pass of a style over a host's frame: the host's
    /// frame carries no surface coordinates and they cannot be rebuilt.
    pub const NO_HOST_UV: &str = "E0321";
    /// A line set's `dash:` that is not one or two lengths in px over 0
    /// (`dash: 6px`, `dash: dashes(6px, 4px)`).
    pub const BAD_LINE_DASH: &str = "E0323";
    /// A texture file is missing or unreadable.
    pub const MISSING_TEXTURE: &str = "E0401";
    /// A mesh file is missing or unreadable.
    pub const UNREADABLE_MESH: &str = "E0402";
    /// The scene lacks a vertex attribute the style needs (UVs, tangents).
    pub const MISSING_ATTRIBUTE: &str = "E0403";
    /// A size or resource request past a stated limit.
    pub const LIMIT_EXCEEDED: &str = "E0404";
    /// A scene file is malformed.
    pub const BAD_SCENE: &str = "E0405";
    /// A file named by a style or scene that is absolute or outside the root (docs/PATHS.md).
    pub const PATH_OUTSIDE_ROOT: &str = "E0406";
    /// A style's test file (`<style>.tests.toml`, `npr test`) is malformed:
    /// not TOML, an unknown or missing field, a value of the wrong type or
    /// outside its domain, a scene or style it names that does not exist.
    pub const BAD_TEST_FILE: &str = "E0407";
    /// A test's golden image is missing (and `--bless` was not given), not
    /// an image, or not the size the test renders.
    pub const BAD_GOLDEN: &str = "E0408";
    /// A glTF material, texture, image or sampler refers to one that does
    /// not exist (an index out of range), at its glTF path.
    pub const BAD_MATERIAL_REFERENCE: &str = "E0409";
    /// A glTF material's image that cannot be used: it does not decode, is
    /// not PNG, or its bytes cannot be read; at its glTF path.
    pub const BAD_MATERIAL_IMAGE: &str = "E0410";
    /// A host input (`input(...)` in the style; `npr render --input`,
    /// `--inputs`) that is not given, not an image, missing a layer, of
    /// another size than the others, or holding values outside its kind's
    /// convention (a non-finite or negative depth).
    pub const BAD_INPUT: &str = "E0420";
    /// A frame of a host input sequence (`--input NAME='beauty/{frame}.png'`,
    /// `--inputs 'shots/{frame:04}.exr'`) whose file does not exist.
    pub const INPUT_FRAME_MISSING: &str = "E0421";
    /// A frame of a host input sequence of another size than the
    /// sequence's first frame.
    pub const INPUT_FRAME_SIZE: &str = "E0422";
    /// Warning: a scene binds a per-object value to a name the style does not read per object.
    pub const UNUSED_BINDING: &str = "W0401";
    /// Warning: a `render(tag)` or `compute(domain, tag)` pass whose tag no object of the scene has.
    pub const ABSENT_TAG: &str = "W0402";
    /// The command line does not parse (clap's message, exit 1).
    pub const USAGE: &str = "E0501";
    /// A command-line value outside what it may be (`--fps 0`, `--time nan`, `--eye` of a mono scene).
    pub const BAD_ARGUMENT_VALUE: &str = "E0502";
    /// An output file or directory cannot be written.
    pub const CANNOT_WRITE: &str = "E0503";
    /// A directory given to `--compiled` is not a valid compiled style.
    pub const BAD_COMPILED_DIR: &str = "E0504";
    /// No GPU adapter (or software driver) is available.
    pub const NO_DEVICE: &str = "E0505";
    /// A benchmark cannot run on what it was given.
    pub const BENCH_UNSUPPORTED: &str = "E0506";
    /// `npr studio` cannot serve (the port is taken, the host cannot be
    /// bound), or `npr watch`/`npr studio` cannot watch the files.
    pub const CANNOT_SERVE: &str = "E0507";
    /// The GPU cannot allocate the textures or buffers a frame needs.
    pub const GPU_OUT_OF_MEMORY: &str = "E0508";
    /// The GPU device was lost (a driver reset, the device destroyed) while npr used it.
    pub const DEVICE_LOST: &str = "E0509";
    /// The device (or its adapter) lacks a WebGPU feature, or a limit above
    /// the default, that a pass of the style needs (`Manifest::device_needs`).
    pub const DEVICE_LACKS_NEED: &str = "E0510";
    /// A video output (`-o NAME.mp4`, `.webm`) whose encoder, the system's
    /// ffmpeg, is not installed or lacks the codec.
    pub const NO_VIDEO_ENCODER: &str = "E0511";
    /// A checkpoint (`--checkpoints`) made for another style, scene, size,
    /// frame rate or npr version.
    pub const CHECKPOINT_MISMATCH: &str = "E0512";
    /// A checkpoint file that is not one, or is truncated or corrupted.
    pub const BAD_CHECKPOINT: &str = "E0513";
    /// A host application (the embedding API, `npr_runner::embed`) used a mesh
    /// handle that was removed or that another runtime gave out.
    pub const UNKNOWN_MESH: &str = "E0601";
    /// A host application gave a texture view the runtime cannot render
    /// into: an sRGB, depth or integer format, no `RENDER_ATTACHMENT`
    /// usage, not one 2D layer and mip, a size outside the limits, or
    /// views that do not fit the style's eyes.
    pub const BAD_RENDER_TARGET: &str = "E0602";
    /// A host application gave `StyleRuntime::update_mesh` vertices that do
    /// not fit the mesh: another vertex count, non-finite numbers, tangents
    /// for a mesh without UVs, or a mesh whose vertices the runtime derives
    /// itself (an animated primitive, a patch of a patched surface).
    pub const BAD_MESH_UPDATE: &str = "E0603";
    /// A host application gave `StyleRuntime::set_input` a name the style
    /// declares no `input(...)` texture of.
    pub const UNKNOWN_HOST_INPUT: &str = "E0604";
    /// A host application gave `StyleRuntime::set_input` a texture view the
    /// input cannot be read from (not 2D, one layer, mip and sample; no
    /// `TEXTURE_BINDING`; a format not read as floats), or a convention
    /// not of the input's kind.
    pub const BAD_HOST_INPUT: &str = "E0605";
    /// A host input of another size than the target a frame renders into.
    pub const HOST_INPUT_SIZE: &str = "E0606";
    /// A frame of a style that reads a host input the host has not given.
    pub const MISSING_HOST_INPUT: &str = "E0607";
    /// A Bevy camera drawn by a style that reads an input the camera does
    /// not produce: depth without `DepthPrepass`, normals without
    /// `NormalPrepass`, motion without `MotionVectorPrepass`, or a kind Bevy
    /// renders no image of (ids, free-form images).
    pub const BEVY_INPUT_NOT_PRODUCED: &str = "E0608";
    /// A Bevy camera whose frame a style over inputs cannot read as the
    /// camera is set up: multisampled prepass textures (MSAA on), or a
    /// viewport (a part of the target).
    pub const BEVY_INPUT_UNREADABLE: &str = "E0609";
    /// A host's pose whose joint matrices do not fit its mesh's skin:
    /// another number of them than the skin's joints, or a pose for a mesh
    /// registered without a skin (the embedding API's `SkinPose`; in Bevy,
    /// a `SkinnedMesh` whose joint entities are missing or do not match
    /// its mesh).
    pub const POSE_JOINTS: &str = "E0612";
    /// A host's pose with a joint matrix or morph weight that is not finite.
    pub const NON_FINITE_POSE: &str = "E0613";
    /// A host's pose with another number of morph weights than its mesh
    /// has morph targets.
    pub const POSE_MORPH_WEIGHTS: &str = "E0614";
    /// A host's skin or morph targets that do not fit the mesh it registers
    /// them with (`StyleRuntime::add_skinned_mesh`): joint indices or
    /// weights not one set per vertex, weights not summing to 1, a joint
    /// past the skin's, too many joints, morph deltas not one per vertex.
    pub const BAD_SKIN: &str = "E0615";
    /// A frame's camera (embedding API) whose projection cannot be drawn
    /// with: a field of view outside (0, π), a near plane not past the eye,
    /// a far plane not past the near one, a negative or non-finite IPD.
    pub const BAD_HOST_CAMERA: &str = "E0616";
    /// Internal compiler error (a bug in npr, not in the style).
    pub const INTERNAL: &str = "E9001";

    /// [`ALL`] as the Markdown table of `docs/ERRORS.md` (checked by
    /// `dsl/tests/error_docs.rs`).
    pub fn markdown_table() -> String {
        let mut t = String::from("| code | meaning |\n|---|---|\n");
        for (code, what) in ALL {
            t.push_str(&format!("| {code} | {what} |\n"));
        }
        t.push_str(&format!("| {INTERNAL} | internal error: a bug in npr (exit 2) |\n"));
        t
    }

    /// Every user-facing code with a one-line description (for `npr explain` and the docs).
    pub const ALL: &[(&str, &str)] = &[
        (SYNTAX, "syntax error"),
        (STYLE_HEADER, "missing or repeated style header"),
        (DUPLICATE_NAME, "name declared twice"),
        (BAD_USE, "bad use of another file"),
        (NESTED_TOO_DEEP, "nested too deeply"),
        (EXPRESSION_TOO_DEEP, "expression too deep"),
        (NOT_UTF8, "file is not UTF-8 text"),
        (UNKNOWN_NAME, "unknown name"),
        (UNKNOWN_OPERATOR, "unknown operator"),
        (BAD_ARGUMENT, "bad argument"),
        (UNKNOWN_TYPE, "unknown type, format or field"),
        (TYPE_MISMATCH, "type mismatch"),
        (UNIT_MISMATCH, "unit mismatch"),
        (OUT_OF_RANGE, "value outside its declared range"),
        (NOT_CONSTANT, "expression must be constant"),
        (COLOR_ALPHA_CHANGED, "colour arithmetic that changes alpha (warning)"),
        (
            BAD_GRADIENT,
            "bad gradient: no stops, unsorted, or a position outside 0..1",
        ),
        (LOG_DOMAIN, "`log` of a value that may be 0 or negative (warning)"),
        (SQRT_DOMAIN, "`sqrt` of a value that may be negative (warning)"),
        (
            POW_DOMAIN,
            "`pow(x, y)` with x < 0, or x = 0 and y ≤ 0, reachable (warning)",
        ),
        (DIVISION_BY_ZERO, "division by a range that holds 0 (warning)"),
        (
            INVERSE_TRIG_DOMAIN,
            "`asin`/`acos` of a value that may leave [−1, 1] (warning)",
        ),
        (NORMALIZE_ZERO, "`normalize` of a vector that may be zero (warning)"),
        (ATAN2_ORIGIN, "`atan2(0, 0)` reachable (warning)"),
        (F16_OVERFLOW, "a value past 65504 stored in an f16 target (warning)"),
        (PASS_CYCLE, "dependency cycle between passes"),
        (FORMAT_MISMATCH, "value incompatible with target format"),
        (NO_OUTPUT, "missing or bad output"),
        (BAD_PASS_INPUT, "bad pass input"),
        (BAD_VALUE_TYPE, "per-object value of a type it cannot have"),
        (STATE_ORDER, "state read before declared, or not updated once"),
        (BAD_STATEMENT, "statement the pass kind does not have"),
        (UNREAD_COMPUTE, "compute pass whose values nothing reads (warning)"),
        (
            PATCH_BLEND_UNOCCLUDED,
            "`patch.weight` read without a depth test against an earlier pass (warning)",
        ),
        (NOT_BLENDABLE, "blend on a format that cannot be blended"),
        (DEPTH_NOT_KEPT, "depth test against a pass that keeps no depth"),
        (BAD_ID_TARGET, "a pass over pixels of a target that is not an ID target"),
        (BAD_FILTER, "not an art-map filter, or a filter used as a style"),
        (CANNOT_TILE, "`schedule: tiled` on a pass that cannot be tiled"),
        (
            CANNOT_RECOMPUTE,
            "`schedule: recompute` on a pass that its reader cannot compute in its tiles",
        ),
        (UNKNOWN_EDGE_TYPE, "a line set's unknown edge type"),
        (BAD_CREASE_ANGLE, "a line set's crease without an angle in 0..180deg"),
        (EMPTY_LINE_SET, "a line set that selects nothing"),
        (DUPLICATE_LINE_SET, "two line sets with one name"),
        (MISPLACED_LINE_SET, "a line set, or its values, where there can be none"),
        (BAD_LINE_VISIBILITY, "a line set's unknown visibility"),
        (
            NOT_A_TESTED_DEPTH,
            "a depth test against neither a pass nor a depth input",
        ),
        (
            INPUT_DEPTH_MISMATCH,
            "a depth test against the host's depth at another scale or view",
        ),
        (NO_HOST_UV, "`uv` in an image pass over a host's frame"),
        (BAD_LINE_DASH, "a line set's dash that is not lengths in px"),
        (MISSING_TEXTURE, "missing texture file"),
        (UNREADABLE_MESH, "unreadable mesh"),
        (MISSING_ATTRIBUTE, "scene lacks a required attribute"),
        (LIMIT_EXCEEDED, "limit exceeded"),
        (BAD_SCENE, "malformed scene file"),
        (PATH_OUTSIDE_ROOT, "file path absolute or outside the root"),
        (BAD_TEST_FILE, "malformed style test file"),
        (BAD_GOLDEN, "golden image missing, unreadable or of another size"),
        (
            BAD_MATERIAL_REFERENCE,
            "a glTF material, texture or image index out of range",
        ),
        (BAD_MATERIAL_IMAGE, "a glTF material's image does not decode"),
        (
            BAD_INPUT,
            "host input image missing, unreadable, mis-sized or outside its convention",
        ),
        (INPUT_FRAME_MISSING, "a frame of a host input sequence is missing"),
        (
            INPUT_FRAME_SIZE,
            "a frame of a host input sequence differs in size from its first frame",
        ),
        (UNUSED_BINDING, "scene binding the style does not read (warning)"),
        (ABSENT_TAG, "pass over a tag no object has (warning)"),
        (USAGE, "command line does not parse"),
        (BAD_ARGUMENT_VALUE, "bad command-line value"),
        (CANNOT_WRITE, "cannot write an output"),
        (BAD_COMPILED_DIR, "bad compiled style directory"),
        (NO_DEVICE, "no GPU device"),
        (BENCH_UNSUPPORTED, "benchmark cannot run on this input"),
        (CANNOT_SERVE, "cannot serve the studio or watch files"),
        (GPU_OUT_OF_MEMORY, "the GPU ran out of memory"),
        (DEVICE_LOST, "the GPU device was lost"),
        (DEVICE_LACKS_NEED, "the device lacks a feature or limit the style needs"),
        (NO_VIDEO_ENCODER, "the video encoder (ffmpeg) is missing"),
        (CHECKPOINT_MISMATCH, "checkpoint made for another render"),
        (BAD_CHECKPOINT, "checkpoint truncated, corrupted or not one"),
        (UNKNOWN_MESH, "a host used a mesh handle that was removed"),
        (BAD_RENDER_TARGET, "a host's texture view the style cannot render into"),
        (BAD_MESH_UPDATE, "a host's deformed vertices do not fit the mesh"),
        (UNKNOWN_HOST_INPUT, "a host gave an input the style does not declare"),
        (
            BAD_HOST_INPUT,
            "a host's input view or convention the input cannot be read from",
        ),
        (HOST_INPUT_SIZE, "a host's input of another size than the target"),
        (MISSING_HOST_INPUT, "a host did not give an input the style reads"),
        (
            BEVY_INPUT_NOT_PRODUCED,
            "a Bevy camera does not produce an input its style reads",
        ),
        (
            BEVY_INPUT_UNREADABLE,
            "a Bevy camera's frame a style over inputs cannot read (MSAA, a viewport)",
        ),
        (POSE_JOINTS, "a host's pose does not fit its mesh's joints"),
        (NON_FINITE_POSE, "a host's pose has a number that is not finite"),
        (
            POSE_MORPH_WEIGHTS,
            "a host's morph weights do not fit its mesh's targets",
        ),
        (BAD_SKIN, "a host's skin does not fit its mesh"),
        (BAD_HOST_CAMERA, "a host's camera whose projection cannot be drawn with"),
    ];
}
