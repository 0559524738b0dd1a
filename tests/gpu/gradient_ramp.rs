//! `ramp(g, t)` of a `gradient` param on the GPU against the ramp written
//! out in f64 (compiler/src/front/resolve/gradient.rs): linear stops, two
//! stops at one position (a hard edge), and `mode: constant`; folded into
//! the shader and kept live (`--keep-params`: a uniform read by
//! `npr_ramp_g`), and live stops set at run time as a host sets them.

use super::common::{artmaps, gpu};
use npr_abi::param_literal::{read_literal, SettingOrigin};
use npr_abi::param_value::{type_value, ParamShape};
use npr_runner::{FrameSpec, Renderer};

/// (position, colour bytes): the stops of the test's gradients.
const STOPS: [(f64, [u8; 4]); 5] = [
    (0.1, [0x10, 0x20, 0x30, 0xff]),
    (0.4, [0xe0, 0x7a, 0x3a, 0xff]),
    (0.6, [0x40, 0xc0, 0x80, 0x80]),
    (0.6, [0xff, 0xff, 0xff, 0xff]),
    (0.9, [0x00, 0x00, 0xff, 0xff]),
];

fn colour(bytes: [u8; 4]) -> [f64; 4] {
    bytes.map(|b| b as f64 / 255.0)
}

/// The colour at `t`: the first stop's below it, the last's past it, in
/// between the mix of the two stops around `t` (linear), or the colour of
/// the last stop at or before `t` (constant).
fn reference(t: f64, constant: bool) -> [f64; 4] {
    let last_at_or_before = STOPS.iter().rposition(|(p, _)| *p <= t);
    let Some(i) = last_at_or_before else {
        return colour(STOPS[0].1);
    };
    if constant || i + 1 == STOPS.len() {
        return colour(STOPS[i].1);
    }
    let ((p0, c0), (p1, c1)) = (STOPS[i], STOPS[i + 1]);
    let f = (t - p0) / (p1 - p0);
    let (a, b) = (colour(c0), colour(c1));
    [0, 1, 2, 3].map(|k| a[k] + (b[k] - a[k]) * f)
}

const WIDTH: u32 = 200;

fn style(constant: bool) -> String {
    let stops: Vec<String> = STOPS
        .iter()
        .map(|(p, c)| format!("stop({p}, #{:02x}{:02x}{:02x}{:02x})", c[0], c[1], c[2], c[3]))
        .collect();
    let mode = if constant { ", mode: constant" } else { "" };
    format!(
        "style \"Ramp\"\nparam g: gradient = gradient({}{mode})\npass p: image() {{\n  out c: rgba32float = ramp(g, screen_uv.x)\n}}\noutput p.c\n",
        stops.join(", ")
    )
}

fn compile(text: &str, keep_params: bool) -> npr_runner::StyleProgram {
    compile_scheduled(text, keep_params, npr_compiler::ir::Schedule::default())
}

fn compile_scheduled(text: &str, keep_params: bool, schedule: npr_compiler::ir::Schedule) -> npr_runner::StyleProgram {
    // The style reads no file: the repository root is its directory.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut sources = npr_diag::SourceMap::new();
    let opts = npr_compiler::CompileOptions {
        keep_params,
        schedule,
        ..Default::default()
    };
    match npr_compiler::compile_source("case.npr", text, dir, &mut sources, &opts) {
        Ok(c) => c.program(),
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(e) => panic!("{e:?}"),
    }
}

fn scene() -> npr_runner::scene::Scene {
    artmaps::scene("[camera]\nposition = [0.0, 0.0, 2.0]\ntarget = [0.0, 0.0, 0.0]\n")
}

/// One row of `WIDTH` texels, `t` = screen u at each texel's centre.
fn row(r: &mut Renderer, scene: &npr_runner::scene::Scene) -> Vec<[f32; 4]> {
    r.render(scene, &FrameSpec::still(WIDTH, 1, 0)).expect("render");
    let img = r.read_output().expect("read");
    (0..WIDTH).map(|x| img.texel(x, 0)).collect()
}

fn t_at(x: u32) -> f64 {
    (x as f64 + 0.5) / WIDTH as f64
}

/// Every texel within 1e-5 of `want(t)`: f32 arithmetic of a few
/// operations on values in 0..1.
fn assert_row(got: &[[f32; 4]], want: impl Fn(f64) -> [f64; 4], what: &str) {
    for (x, g) in got.iter().enumerate() {
        let t = t_at(x as u32);
        let w = want(t);
        for k in 0..4 {
            assert!(
                (g[k] as f64 - w[k]).abs() < 1e-5,
                "{what}, t = {t}, channel {k}: GPU {g:?} vs f64 {w:?}"
            );
        }
    }
}

#[test]
fn ramp_matches_the_f64_rule_on_the_gpu() {
    let scene = scene();
    for constant in [false, true] {
        let program = compile(&style(constant), false);
        assert!(
            program.manifest.params.iter().all(|p| p.name != "g"),
            "a folded gradient is a constant of the shader, not a parameter"
        );
        let g = gpu();
        let mut r = Renderer::new(&g.device, &g.queue, &program, &scene).expect("renderer");
        let got = row(&mut r, &scene);
        assert_row(
            &got,
            |t| reference(t, constant),
            &format!("folded, constant: {constant}"),
        );
    }
}

/// Kept live, the same stops give the same row as folded (every texel
/// within 1e-6: the same operations on the same f32 values, from a
/// uniform instead of constants) and as the f64 rule; new stops set as a
/// host's `set_param` sets them (`npr_abi::param_value::type_value` into the
/// manifest's default, which the runner packs into the uniform) re-render
/// without a recompile and follow `npr_abi::gradient::ramp` in f64.
#[test]
fn a_live_gradient_matches_the_folded_one_and_takes_new_stops() {
    let scene = scene();
    for constant in [false, true] {
        let g = gpu();
        let folded = {
            let program = compile(&style(constant), false);
            let mut r = Renderer::new(&g.device, &g.queue, &program, &scene).expect("renderer");
            row(&mut r, &scene)
        };
        let program = compile(&style(constant), true);
        let index = program
            .manifest
            .params
            .iter()
            .position(|p| p.name == "g")
            .expect("g is a param");
        let p = &program.manifest.params[index];
        assert_eq!(
            (p.ty.as_str(), p.binding),
            ("gradient", npr_abi::manifest::ParamBinding::Uniform)
        );
        assert_eq!(
            program.manifest.style_uniform_size,
            16 * npr_abi::gradient::GRADIENT_SLOTS as u64
        );
        let shader = program.shaders.values().map(String::as_str).collect::<String>();
        assert!(
            shader.contains("npr_ramp_g(") && shader.contains("params.p_g["),
            "the live ramp reads the uniform"
        );
        let mut r = Renderer::new(&g.device, &g.queue, &program, &scene).expect("renderer");
        let live = row(&mut r, &scene);
        for (x, (a, b)) in live.iter().zip(&folded).enumerate() {
            for k in 0..4 {
                assert!(
                    (a[k] - b[k]).abs() <= 1e-6,
                    "constant: {constant}, texel {x}, channel {k}: live {a:?} vs folded {b:?}"
                );
            }
        }
        assert_row(
            &live,
            |t| reference(t, constant),
            &format!("live, constant: {constant}"),
        );

        let text = "0:#ff0000, 0.25:#00ff0080, 0.5:#0000ff, 0.5:#ffffff, 1:#000000";
        let typed = type_value(
            &ParamShape::of_manifest(&r.manifest().params[index]),
            &read_literal(text),
            text,
            &SettingOrigin::Host,
        )
        .expect("stops type as a gradient value");
        r.params_mut()[index].default = typed.value.clone();
        let (stops, kept_mode) = npr_abi::gradient::unpack(&typed.value).expect("packed stops");
        assert_eq!(kept_mode, constant, "new stops keep the declared mode");
        let set = row(&mut r, &scene);
        assert_row(
            &set,
            |t| npr_abi::gradient::ramp(&stops, constant, t),
            &format!("set live, constant: {constant}"),
        );
    }
}

/// A manifest is untrusted until validated: a live gradient's slots are
/// counted in the style block's size, its offset must leave room for all
/// 21, and its value must be their 84 components.
#[test]
fn a_live_gradient_manifest_is_validated_slot_by_slot() {
    let program = compile(&style(false), true);
    let good = &program.manifest;
    good.validate().expect("the compiled manifest is valid");
    let index = good.params.iter().position(|p| p.name == "g").expect("g");
    let mut short = good.clone();
    short.params[index].default.truncate(80);
    let err = short.validate().expect_err("a short value").to_string();
    assert!(err.contains(&format!("params[{index}].default")), "{err}");
    let mut one_slot = good.clone();
    one_slot.style_uniform_size = 16;
    let err = one_slot.validate().expect_err("a block of one slot").to_string();
    assert!(err.contains("style_uniform_size"), "{err}");
    let mut late = good.clone();
    late.params[index].offset = Some(16);
    let err = late.validate().expect_err("slots past the block").to_string();
    assert!(err.contains(&format!("params[{index}].offset")), "{err}");
}

/// Every schedule emits the live ramp (a tiled image pass copies it into
/// its compute module): each gives the folded row within 1e-6.
#[test]
fn a_live_gradient_is_the_same_under_every_schedule() {
    let scene = scene();
    let g = gpu();
    let folded = {
        let program = compile(&style(false), false);
        let mut r = Renderer::new(&g.device, &g.queue, &program, &scene).expect("renderer");
        row(&mut r, &scene)
    };
    for schedule in npr_compiler::ir::Schedule::ALL {
        let program = compile_scheduled(&style(false), true, schedule);
        let mut r = Renderer::new(&g.device, &g.queue, &program, &scene).expect("renderer");
        let live = row(&mut r, &scene);
        for (x, (a, b)) in live.iter().zip(&folded).enumerate() {
            for k in 0..4 {
                assert!(
                    (a[k] - b[k]).abs() <= 1e-6,
                    "--schedule {}, texel {x}, channel {k}: live {a:?} vs folded {b:?}",
                    schedule.name()
                );
            }
        }
    }
}
