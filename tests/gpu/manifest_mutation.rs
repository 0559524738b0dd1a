//! Property test: a compiled manifest with its JSON mutated (numbers out of
//! range, fields deleted, types swapped, arrays truncated or duplicated)
//! never panics `StyleProgram::load_dir`; and whatever passes its validation
//! never panics `Renderer::new` or a small render either (Ok or Err only).
//! Plus: the pristine directory loads and renders, and a few mutations are
//! rejected naming the bad field.

use crate::common;

use common::{gpu, root};
use npr_abi::StyleProgram;
use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use npr_runner::{FrameSpec, Renderer};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;

/// Styles with render and image passes, a noise texture, aliased targets,
/// style and per-object uniforms (parameters kept), compute passes over
/// vertices and objects with per-object values read by a render pass, a kept
/// depth tested by another pass and a blend mode.
const STYLES: &[&str] = &[
    "examples/edge_breakup.npr",
    "examples/rounded_shadows.npr",
    "examples/object_centroids.npr",
    "examples/overlay_lines.npr",
];

/// A compiled style: its manifest as JSON and its (file, WGSL) shaders.
type Compiled = (Value, Vec<(String, String)>);

fn compiled() -> &'static Vec<Compiled> {
    static C: OnceLock<Vec<Compiled>> = OnceLock::new();
    C.get_or_init(|| {
        STYLES
            .iter()
            .map(|s| {
                let mut sources = SourceMap::new();
                let opts = CompileOptions {
                    keep_params: true,
                    ..Default::default()
                };
                let c = npr_compiler::compile_file(&root().join(s), &mut sources, &opts)
                    .unwrap_or_else(|_| panic!("{s} compiles"));
                (serde_json::to_value(&c.manifest).expect("json"), c.shaders.clone())
            })
            .collect()
    })
}

fn scene() -> &'static npr_runner::scene::Scene {
    static S: OnceLock<npr_runner::scene::Scene> = OnceLock::new();
    S.get_or_init(|| {
        let mut sources = SourceMap::new();
        npr_runner::scene::load_scene(&root().join("examples/scenes/spheres.toml"), &mut sources).expect("scene")
    })
}

fn write_dir(dir: &Path, manifest: &Value, shaders: &[(String, String)]) {
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir).expect("temp dir");
    for (file, wgsl) in shaders {
        std::fs::write(dir.join(file), wgsl).expect("write shader");
    }
    std::fs::write(
        dir.join("manifest.json"),
        serde_json::to_string_pretty(manifest).expect("json"),
    )
    .expect("write");
}

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("npr-manifest-mutation-{}-{name}", std::process::id()))
}

/// Every value's path in the tree (object keys and array indices).
fn paths(v: &Value, here: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    out.push(here.clone());
    match v {
        Value::Object(m) => {
            for (k, c) in m {
                here.push(Step::Key(k.clone()));
                paths(c, here, out);
                here.pop();
            }
        }
        Value::Array(a) => {
            for (i, c) in a.iter().enumerate() {
                here.push(Step::Index(i));
                paths(c, here, out);
                here.pop();
            }
        }
        _ => {}
    }
}

#[derive(Debug, Clone)]
enum Step {
    Key(String),
    Index(usize),
}

fn at<'a>(v: &'a mut Value, path: &[Step]) -> Option<&'a mut Value> {
    let mut v = v;
    for s in path {
        v = match s {
            Step::Key(k) => v.get_mut(k.as_str())?,
            Step::Index(i) => v.get_mut(*i)?,
        };
    }
    Some(v)
}

/// Numbers a mutation may write: out of range, negative, fractional, huge, or plausible.
const NUMBERS: &[f64] = &[
    -1.0,
    0.0,
    1.0,
    2.0,
    3.0,
    7.0,
    17.0,
    255.0,
    4096.0,
    65536.0,
    4294967296.0,
    1e300,
    -0.5,
    0.5,
    1.5,
    100.0,
];

#[derive(Debug, Clone)]
enum Mutation {
    Number(usize),
    Delete,
    SwapType(usize),
    Truncate(usize),
    Duplicate,
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (0..NUMBERS.len()).prop_map(Mutation::Number),
        2 => Just(Mutation::Delete),
        2 => (0..6usize).prop_map(Mutation::SwapType),
        1 => (0..3usize).prop_map(Mutation::Truncate),
        1 => Just(Mutation::Duplicate),
    ]
}

fn apply(root: &mut Value, path: &[Step], m: &Mutation) {
    match m {
        Mutation::Number(n) => {
            if let Some(v) = at(root, path) {
                if v.is_number() || v.is_null() {
                    *v = serde_json::Number::from_f64(NUMBERS[*n]).map_or(Value::Null, Value::Number);
                    if NUMBERS[*n].fract() == 0.0 && NUMBERS[*n].abs() < 1e18 {
                        *v = Value::from(NUMBERS[*n] as i64);
                    }
                }
            }
        }
        Mutation::Delete => {
            let Some((last, parent)) = path.split_last() else {
                return;
            };
            match (at(root, parent), last) {
                (Some(Value::Object(o)), Step::Key(k)) => {
                    o.remove(k);
                }
                (Some(Value::Array(a)), Step::Index(i)) => {
                    a.remove(*i);
                }
                _ => {}
            }
        }
        Mutation::SwapType(t) => {
            if let Some(v) = at(root, path) {
                *v = match t {
                    0 => Value::from("x"),
                    1 => Value::from(true),
                    2 => Value::Null,
                    3 => Value::Array(vec![]),
                    4 => Value::Object(Default::default()),
                    _ => Value::from(-3),
                };
            }
        }
        Mutation::Truncate(k) => {
            if let Some(Value::Array(a)) = at(root, path) {
                a.truncate(*k);
            }
        }
        Mutation::Duplicate => {
            let Some((last, parent)) = path.split_last() else {
                return;
            };
            if let (Some(Value::Array(a)), Step::Index(i)) = (at(root, parent), last) {
                let copy = a[*i].clone();
                a.insert(*i, copy);
            }
        }
    }
}

/// Mutated manifests that passed validation (so reached the renderer).
static VALID: AtomicUsize = AtomicUsize::new(0);

/// Load, and when valid, build a renderer and render 64×64: Ok or Err, never a panic.
fn load_and_render(dir: &Path) -> Result<(), String> {
    let program = StyleProgram::load_dir(dir).map_err(|e| e.to_string())?;
    VALID.fetch_add(1, Ordering::Relaxed);
    let scene = scene();
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, scene).map_err(|e| e.to_string())?;
    r.render(scene, &FrameSpec::still(64, 64, 0))
        .map_err(|e| e.to_string())?;
    r.read_output().map(|_| ()).map_err(|e| e.to_string())
}

#[test]
fn pristine_compiled_dirs_load_and_render() {
    for (i, (manifest, shaders)) in compiled().iter().enumerate() {
        let dir = scratch(&format!("pristine{i}"));
        write_dir(&dir, manifest, shaders);
        load_and_render(&dir).unwrap_or_else(|e| panic!("{}: {e}", STYLES[i]));
        let _ = std::fs::remove_dir_all(&dir);
    }
}

#[test]
fn bad_indices_are_rejected_naming_the_field() {
    let (manifest, shaders) = &compiled()[0];
    let cases: &[(&[&str], Value, &str)] = &[
        (&["output"], Value::from(99), "`output`"),
        (&["version"], Value::from(1), "`version`"),
        (&["targets", "0", "physical"], Value::from(99), "`targets[0].physical`"),
        (
            &["passes", "0", "outputs", "0"],
            Value::from(99),
            "`passes[0].outputs[0]`",
        ),
        (
            &["passes", "0", "shader"],
            Value::from("../x.wgsl"),
            "`passes[0].shader`",
        ),
        (
            &["passes", "0", "kind", "fragment_entry"],
            Value::from("fs main"),
            "`passes[0].kind.fragment_entry`",
        ),
        (&["style_uniform_size"], Value::from(4), "`style_uniform_size`"),
        (&["params", "0", "offset"], Value::from(100000), "`params[0].offset`"),
        (
            &["textures", "0", "source", "size"],
            Value::from(0),
            "`textures[0].source.size`",
        ),
    ];
    let dir = scratch("named");
    for (path, value, field) in cases {
        let mut m = manifest.clone();
        let steps: Vec<Step> = path
            .iter()
            .map(|s| s.parse().map_or(Step::Key(s.to_string()), Step::Index))
            .collect();
        *at(&mut m, &steps).unwrap_or_else(|| panic!("{path:?} exists")) = value.clone();
        write_dir(&dir, &m, shaders);
        let err = StyleProgram::load_dir(&dir).expect_err("invalid").to_string();
        assert!(err.contains(field), "{path:?}: {err}");
    }
    // A missing shader file.
    write_dir(&dir, manifest, &shaders[1..]);
    let err = StyleProgram::load_dir(&dir).expect_err("missing shader").to_string();
    assert!(err.contains(&shaders[0].0), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_depth_tests_and_blends_are_rejected_naming_the_field() {
    let overlay = STYLES
        .iter()
        .position(|s| s.ends_with("overlay_lines.npr"))
        .expect("overlay style");
    let (manifest, shaders) = &compiled()[overlay];
    assert_eq!(
        manifest["passes"][1]["name"], "lines",
        "overlay_lines: `lines` tests `shade`"
    );
    let dir = scratch("depth-blend");
    // (what, the edit, the field the error must name).
    type Edit = fn(&mut Value);
    let mutations: &[(&str, Edit, &str)] = &[
        (
            "a test of a pass that runs later",
            |m| m["passes"][1]["kind"]["depth"]["pass"] = Value::from(2),
            "`passes[1].kind.depth.pass`",
        ),
        (
            "a test of a pass that keeps no depth",
            |m| {
                m["passes"][0]["kind"].as_object_mut().expect("kind").remove("depth");
            },
            "`passes[1].kind.depth.pass`",
        ),
        (
            "a test of the host's depth naming no `input(depth)`",
            |m| m["passes"][1]["kind"]["depth"] = serde_json::json!({"mode": "test_input", "input": 0}),
            "`passes[1].kind.depth.input`",
        ),
        (
            "a negative bias",
            |m| m["passes"][1]["kind"]["depth"]["bias_px"] = Value::from(-1.0),
            "`passes[1].kind.depth.bias_px`",
        ),
        (
            "more blend modes than outputs",
            |m| {
                m["passes"][1]["blend"]
                    .as_array_mut()
                    .expect("blend")
                    .push(Value::from("add"))
            },
            "`passes[1].blend`",
        ),
    ];
    for (what, mutate, field) in mutations {
        let mut m = manifest.clone();
        mutate(&mut m);
        write_dir(&dir, &m, shaders);
        let err = StyleProgram::load_dir(&dir).expect_err(what).to_string();
        assert!(err.contains(field), "{what}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn patch_weights_in_a_compute_pass_are_rejected_naming_the_field() {
    let centroids = STYLES
        .iter()
        .position(|s| s.ends_with("object_centroids.npr"))
        .expect("centroids style");
    let (manifest, shaders) = &compiled()[centroids];
    let (pi, count) = manifest["passes"]
        .as_array()
        .expect("passes")
        .iter()
        .enumerate()
        .find_map(|(i, p)| {
            let count = p["kind"]["attributes"].as_array()?.len();
            (p["kind"]["kind"] == "compute").then_some((i, count))
        })
        .expect("a compute pass with attributes");
    let mut m = manifest.clone();
    m["passes"][pi]["kind"]["attributes"]
        .as_array_mut()
        .expect("attributes")
        .push(Value::from("patch_weight"));
    let dir = scratch("compute-patch-weight");
    write_dir(&dir, &m, shaders);
    let err = StyleProgram::load_dir(&dir)
        .expect_err("patch weights in compute")
        .to_string();
    let field = format!("`passes[{pi}].kind.attributes[{count}]`");
    assert!(err.contains(&field) && err.contains("patch weights"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn mutated_manifests_never_panic() {
    let config = Config {
        cases: 256,
        failure_persistence: None,
        ..Config::default()
    };
    let mut runner = TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha));
    let dir = scratch("mutated");
    let strategy = (
        0..STYLES.len(),
        proptest::collection::vec((any::<prop::sample::Index>(), mutation()), 1..=2),
    );
    let result = runner.run(&strategy, |(style, mutations)| {
        let (manifest, shaders) = &compiled()[style];
        let mut m = manifest.clone();
        for (index, mutation) in &mutations {
            let mut all = Vec::new();
            paths(&m, &mut Vec::new(), &mut all);
            let path = index.get(&all).clone();
            apply(&mut m, &path, mutation);
        }
        write_dir(&dir, &m, shaders);
        let _ = load_and_render(&dir);
        Ok(())
    });
    let _ = std::fs::remove_dir_all(&dir);
    result.unwrap_or_else(|e| panic!("{e}"));
    // Some mutations must get past validation, or the renderer is not exercised.
    let valid = VALID.load(Ordering::Relaxed);
    eprintln!("{valid} of 256 mutated manifests passed validation and were rendered");
    assert!(valid >= 30, "only {valid} mutated manifests reached the renderer");
}
