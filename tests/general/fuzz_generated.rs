//! A grammar-aware generator of valid-looking styles (issue 13): params of
//! every kind, a render pass and image passes reading it (some with a
//! `schedule:` setting), `let`s, typed
//! expressions over builtins, intrinsics, swizzles, `if`s, target reads and
//! params, every target format. Each generated style either compiles, and
//! then every WGSL module it emits is validated again here by naga, or is
//! refused with user errors; never an internal error (E9001), never a
//! panic. Most must compile, or the generator tests nothing.
//!
//! Deterministic: case `k` is generated from seed `k`, so a failure names
//! its case and prints its style. `NPR_FUZZ_CASES` sets the count for a
//! soak run and `NPR_FUZZ_FIRST` its first seed (docs/FUZZING.md).

use crate::common;

use npr_compiler::{CompileError, CompileOptions};
use npr_diag::SourceMap;

/// A small deterministic generator (SplitMix64).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len())]
    }
    fn chance(&mut self, percent: usize) -> bool {
        self.below(100) < percent
    }
    fn float(&mut self) -> String {
        format!("{:.3}", self.below(4000) as f64 / 1000.0 - 1.0)
    }
}

/// Expression types the generator builds.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum T {
    F,
    V2,
    V3,
    V4,
}

impl T {
    fn width(self) -> usize {
        match self {
            T::F => 1,
            T::V2 => 2,
            T::V3 => 3,
            T::V4 => 4,
        }
    }
    fn of_width(n: usize) -> T {
        [T::F, T::V2, T::V3, T::V4][n - 1]
    }
    fn ctor(self) -> &'static str {
        ["", "vec2", "vec3", "vec4"][self.width() - 1]
    }
}

/// What expressions of a pass may name.
struct Scope {
    /// Render pass (geometry builtins) or image pass.
    render: bool,
    /// Names with their types: params and earlier `let`s.
    names: Vec<(String, T)>,
    /// Target reads `pass.target` with their widths (image passes).
    reads: Vec<(String, usize)>,
}

const SWIZ: [&str; 4] = ["x", "y", "z", "w"];
const RGBA: [&str; 4] = ["r", "g", "b", "a"];

fn expr(r: &mut Rng, s: &Scope, t: T, depth: usize) -> String {
    if depth == 0 || r.chance(20) {
        return leaf(r, s, t);
    }
    let d = depth - 1;
    match (t, r.below(9)) {
        (_, 0) => format!("({} + {})", expr(r, s, t, d), expr(r, s, t, d)),
        (_, 1) => format!("({} * {})", expr(r, s, t, d), expr(r, s, T::F, d)),
        (_, 2) => format!("({} - {})", expr(r, s, t, d), expr(r, s, t, d)),
        (_, 3) => format!(
            "{}({})",
            r.pick(&["abs", "fract", "sin", "cos", "floor", "sqrt", "exp2"]),
            expr(r, s, t, d)
        ),
        (_, 4) => format!(
            "clamp({}, {}, {})",
            expr(r, s, t, d),
            broadcast(t, "0.0"),
            broadcast(t, "1.0")
        ),
        (_, 5) => format!(
            "mix({}, {}, {})",
            expr(r, s, t, d),
            expr(r, s, t, d),
            expr(r, s, T::F, d)
        ),
        (_, 6) => format!(
            "if {} > {} {{ {} }} else {{ {} }}",
            expr(r, s, T::F, d),
            expr(r, s, T::F, d),
            expr(r, s, t, d),
            expr(r, s, t, d)
        ),
        (T::F, 7) => {
            let v = *r.pick(&[T::V2, T::V3, T::V4]);
            format!("length({})", expr(r, s, v, d))
        }
        (T::F, _) => {
            let v = *r.pick(&[T::V2, T::V3]);
            format!("dot({}, {})", expr(r, s, v, d), expr(r, s, v, d))
        }
        (T::V3, 7) => format!("cross({}, {})", expr(r, s, T::V3, d), expr(r, s, T::V3, d)),
        (_, 7) => format!("normalize({} + {})", expr(r, s, t, d), broadcast(t, "0.5")),
        (_, _) => {
            // A constructor from narrower parts, or a swizzle of a wider value.
            if r.chance(50) {
                let mut parts = Vec::new();
                let mut left = t.width();
                while left > 0 {
                    let w = 1 + r.below(left);
                    parts.push(expr(r, s, T::of_width(w), d));
                    left -= w;
                }
                format!("{}({})", t.ctor(), parts.join(", "))
            } else {
                // From a vector at least as wide (a scalar has no swizzle).
                let lo = t.width().max(2);
                let from = T::of_width(lo + r.below(5 - lo));
                let letters = if r.chance(50) { SWIZ } else { RGBA };
                let sw: String = (0..t.width()).map(|_| letters[r.below(from.width())]).collect();
                format!("({}).{sw}", expr(r, s, from, d))
            }
        }
    }
}

fn broadcast(t: T, v: &str) -> String {
    match t {
        T::F => v.to_string(),
        _ => format!("{}({v})", t.ctor()),
    }
}

fn leaf(r: &mut Rng, s: &Scope, t: T) -> String {
    let named: Vec<&(String, T)> = s.names.iter().filter(|(_, nt)| *nt == t).collect();
    if !named.is_empty() && r.chance(40) {
        return r.pick(&named).0.clone();
    }
    let reads: Vec<&(String, usize)> = s.reads.iter().filter(|(_, w)| *w >= t.width()).collect();
    if !reads.is_empty() && r.chance(50) {
        let (name, w) = r.pick(&reads);
        return if *w == t.width() {
            name.clone()
        } else {
            let sw: String = SWIZ[..t.width()].concat();
            format!("{name}.{sw}")
        };
    }
    // Builtins with units (s, m, px) make most mixes a unit error (E0202),
    // which is a right answer but tests little past typecheck: rarely.
    let with_units: &[&str] = match (t, s.render) {
        (T::F, true) => &["time", "depth", "camera.near"],
        (T::F, false) => &["time", "camera.far"],
        (T::V2, _) => &["resolution"],
        (T::V3, true) => &["position", "camera.position"],
        (T::V3, false) => &["camera.position"],
        (T::V4, _) => &[],
    };
    if !with_units.is_empty() && r.chance(4) {
        return r.pick(with_units).to_string();
    }
    let builtins: &[&str] = match (t, s.render) {
        (T::F, _) => &["light.intensity"],
        (T::V2, true) => &["uv", "screen_uv"],
        (T::V2, false) => &["screen_uv"],
        (T::V3, true) => &["normal", "view_dir", "light.dir", "light.color", "normal.view"],
        (T::V3, false) => &["light.dir", "light.color"],
        (T::V4, _) => &[],
    };
    if !builtins.is_empty() && r.chance(60) {
        return r.pick(builtins).to_string();
    }
    match t {
        T::F => r.float(),
        _ => format!("{}({})", t.ctor(), r.float()),
    }
}

/// Formats with their channel counts.
const FORMATS: &[(&str, usize)] = &[
    ("r8unorm", 1),
    ("rg8unorm", 2),
    ("rgba8unorm", 4),
    ("rgba8unorm_srgb", 4),
    ("r16float", 1),
    ("rg16float", 2),
    ("rgba16float", 4),
    ("r32float", 1),
    ("rg32float", 2),
    ("rgba32float", 4),
];

/// Style number `seed` (also handed to Chromium's WGSL compiler by
/// `webgpu_portability`).
pub(crate) fn style(seed: u64) -> String {
    let mut r = Rng(seed);
    let mut out = String::from("style \"Generated\"\n");
    let mut names = Vec::new();
    for i in 0..r.below(5) {
        let (decl, t) = match r.below(6) {
            0 => (format!("param f{i}: float = {} in -1..3", r.float()), T::F),
            // Declared with a unit; used rarely (see `leaf`), so it is
            // mostly folded away or pruned.
            1 if r.chance(20) => (format!("param w{i}: px = {}px in 0px..64px", r.below(64)), T::F),
            1 => (format!("param m{i}: float = {} in -2..2", r.float()), T::F),
            2 => (format!("param c{i}: color = #{:06x}", r.next() & 0xff_ffff), T::V4),
            3 => (format!("param v{i}: vec3 = vec3({}, 0.5, 1.0)", r.float()), T::V3),
            4 => (format!("param n{i}: int = {} in 0..8", r.below(8)), T::F),
            _ => (
                format!("/// A documented param.\nparam a{i}: float = 0.25 in 0..1 animate {{ 0s: 0.0, 2s: 1.0 }}"),
                T::F,
            ),
        };
        out.push_str(&decl);
        out.push('\n');
        let name = decl
            .rsplit("param ")
            .next()
            .unwrap()
            .split(':')
            .next()
            .unwrap()
            .to_string();
        names.push((name, t));
    }
    let depth = 1 + r.below(6);
    // The render pass.
    let mut scope = Scope {
        render: true,
        names: names.clone(),
        reads: Vec::new(),
    };
    out.push_str("pass g: render(scene) {\n");
    for l in 0..r.below(4) {
        let t = *r.pick(&[T::F, T::V2, T::V3, T::V4]);
        out.push_str(&format!("  let l{l} = {}\n", expr(&mut r, &scope, t, depth)));
        scope.names.push((format!("l{l}"), t));
    }
    let mut targets = Vec::new();
    for k in 0..1 + r.below(3) {
        let (fmt, w) = *r.pick(FORMATS);
        out.push_str(&format!(
            "  out t{k}: {fmt} = {}\n",
            expr(&mut r, &scope, T::of_width(w), depth)
        ));
        targets.push((format!("g.t{k}"), w));
    }
    out.push_str("}\n");
    let mut last = targets[0].0.clone();
    // Image passes' `schedule:` settings come from a stream of their own,
    // so every other draw, and each case found by a soak, stays as it was.
    let mut settings = Rng(seed ^ 0x5c4e_d01e);
    // Half the `tiled` settings become `recompute`, drawn from a third
    // stream, so the cases with any other setting stay as they were.
    let mut recompute = Rng(seed ^ 0x7e_c0de);
    // Image passes, each reading what came before.
    for p in 0..r.below(3) {
        let scope = Scope {
            render: false,
            names: names.clone(),
            reads: targets.clone(),
        };
        let inputs: Vec<String> = {
            let mut v: Vec<String> = targets
                .iter()
                .map(|(n, _)| n.split('.').next().unwrap().to_string())
                .collect();
            v.dedup();
            v
        };
        let scale = *r.pick(&["", " scale 1/2", " scale 2"]);
        let (fmt, w) = *r.pick(FORMATS);
        // Mostly none; `tiled` is mostly E0311 here (no generated pass reads
        // around the pixel), and `recompute` E0312, so they are the rarest.
        let schedule = match settings.below(100) {
            0..=69 => "",
            70..=81 => "  schedule: naive\n",
            82..=91 => "  schedule: auto\n",
            _ if recompute.below(2) == 0 => "  schedule: recompute\n",
            _ => "  schedule: tiled\n",
        };
        out.push_str(&format!(
            "pass i{p}: image({}){scale} {{\n{schedule}  out o: {fmt} = {}\n}}\n",
            inputs.join(", "),
            expr(&mut r, &scope, T::of_width(w), depth)
        ));
        targets.push((format!("i{p}.o"), w));
        last = format!("i{p}.o");
    }
    out.push_str(&format!("output {last}\n"));
    out
}

/// Every module of `c` through naga again, independently of the compiler.
fn naga_validates(c: &npr_compiler::Compiled) -> Result<(), String> {
    for (name, wgsl) in &c.shaders {
        let module = naga::front::wgsl::parse_str(wgsl).map_err(|e| format!("{name}: {}", e.emit_to_string(wgsl)))?;
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
            .validate(&module)
            .map_err(|e| format!("{name}: {e:?}"))?;
    }
    Ok(())
}

#[test]
fn generated_styles_compile_to_naga_valid_wgsl_or_get_user_errors() {
    let cases = common::fuzz::cases(400);
    let (mut compiled, mut refused) = (0u32, 0u32);
    let mut refusals: std::collections::BTreeMap<&'static str, u32> = Default::default();
    // Seeds past the CI count that a soak found failing once (docs/FUZZING.md),
    // run every time so the fix stays in.
    const FOUND_BY_SOAK: &[u64] = &[48924, 272687];
    let first = common::fuzz::first_case();
    for seed in (first..first + cases as u64).chain(FOUND_BY_SOAK.iter().copied()) {
        let text = style(seed);
        let mut sources = SourceMap::new();
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            npr_compiler::compile_source(
                "generated.npr",
                &text,
                std::path::Path::new("."),
                &mut sources,
                &CompileOptions::default(),
            )
        }));
        match result {
            Err(_) => panic!("case {seed}: the compiler panicked on:\n{text}"),
            Ok(Ok(c)) => {
                if let Err(e) = naga_validates(&c) {
                    panic!("case {seed}: naga rejects what the compiler emitted: {e}\n{text}");
                }
                compiled += 1;
            }
            Ok(Err(CompileError::User(d))) => {
                assert!(!d.is_empty(), "case {seed}: a user error with no diagnostic");
                for diag in &d {
                    assert_ne!(diag.code, npr_diag::codes::INTERNAL, "case {seed}:\n{text}");
                    *refusals.entry(diag.code).or_default() += 1;
                }
                refused += 1;
            }
            Ok(Err(CompileError::Internal(e))) => panic!(
                "case {seed}: internal error (E9001) on a generated style:\n{text}\n{e}\n{}",
                e.wgsl.clone().unwrap_or_default()
            ),
        }
    }
    eprintln!("{cases} generated styles: {compiled} compiled (naga-valid), {refused} refused: {refusals:?}");
    assert!(
        compiled * 10 >= cases * 6,
        "only {compiled} of {cases} generated styles compiled: the generator makes too few valid styles ({refusals:?})"
    );
}

#[test]
fn the_generator_covers_every_format_and_both_pass_kinds() {
    let all: String = (0..200).map(style).collect();
    for (fmt, _) in FORMATS {
        assert!(all.contains(&format!(": {fmt} =")), "no generated style writes {fmt}");
    }
    for needle in [
        "render(scene)",
        ": image(",
        "scale 1/2",
        "schedule: naive",
        "schedule: auto",
        "schedule: tiled",
        "schedule: recompute",
        "if ",
        "let ",
        "animate",
        ".rg",
        ".xy",
        "mix(",
        "cross(",
    ] {
        assert!(all.contains(needle), "no generated style has `{needle}`");
    }
}
