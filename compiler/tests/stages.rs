//! Unit tests of the middle stages on small styles: prune (what is removed
//! and why), specialize (folded parameters remove branches; specializations
//! chain), allocate (aliasing by lifetime, format and scale) and the
//! internal errors of impossible states.

use npr_abi::manifest::ParamBinding;
use npr_compiler::back::allocate::{allocate, Allocation};
use npr_compiler::ir::*;
use npr_compiler::mid::dag::PassGraph;
use npr_compiler::mid::prune::{prune, Live};
use npr_compiler::report::Report;
use npr_diag::SourceMap;
use std::path::Path;

/// Load, resolve, typecheck and build the DAG of `text`, which must be valid.
fn front(text: &str) -> (Ir, PassGraph) {
    let mut sources = SourceMap::new();
    let mut diags = Vec::new();
    let loaded = npr_compiler::front::load::load_source("t.npr", text, Path::new("."), &mut sources, None, &mut diags);
    let mut ir = npr_compiler::front::resolve::resolve(&loaded, None, None, &mut diags).expect("no internal error");
    npr_compiler::front::typecheck::typecheck(&mut ir, &mut diags);
    let graph = npr_compiler::mid::dag::build(&ir, &mut diags);
    let errors: Vec<String> = diags
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.message.clone())
        .collect();
    assert!(errors.is_empty(), "{errors:?}");
    (ir, graph)
}

fn entries(report: &Report, action: &str) -> Vec<(String, String)> {
    report
        .entries
        .iter()
        .filter(|e| e.action == action)
        .map(|e| (e.what.clone(), e.why.clone()))
        .collect()
}

fn pass_id(ir: &Ir, name: &str) -> PassId {
    PassId(ir.passes.iter().position(|p| p.name == name).expect("pass") as u32)
}

fn target(ir: &Ir, pass: &str, output: u32) -> TargetRef {
    TargetRef {
        pass: pass_id(ir, pass),
        output,
    }
}

// ------------------------------------------------------------------ prune

/// `lines` is declared before the pass whose depth it tests, and nothing
/// reads `scene_depth`'s target; `unused_tester` tests it too but is dead.
const DEPTH: &str = r#"style "depth"
pass lines: render(scene) {
  out ink: rgba8unorm = #000000 { blend: over }
  depth: test(scene_depth, bias: 1px)
}
pass scene_depth: render(scene) {
  out c: r8unorm = 1.0
  depth: keep
}
pass unused_tester: render(scene) {
  out x: r8unorm = 1.0
  depth: test(scene_depth)
}
output lines.ink
"#;

#[test]
fn a_depth_test_runs_after_the_tested_pass_and_keeps_it_live_for_its_depth() {
    let (ir, graph) = front(DEPTH);
    let (lines, kept) = (pass_id(&ir, "lines"), pass_id(&ir, "scene_depth"));
    let at = |p: PassId| graph.order.iter().position(|x| *x == p).expect("ordered");
    assert!(at(kept) < at(lines), "{:?}", graph.order);
    let mut report = Report::default();
    let live = prune(&ir, &graph, &mut report);
    assert_eq!(
        live.passes,
        vec![kept, lines],
        "the dead tester goes, the tested pass stays"
    );
    assert!(live.depth.contains(&kept));
    assert!(!live.targets.contains(&target(&ir, "scene_depth", 0)));
    let removed = entries(&report, "removed");
    assert!(
        removed.contains(&("target `scene_depth.c`".into(), "nothing reads it".into())),
        "{removed:?}"
    );
    assert!(
        removed.contains(&("pass `unused_tester`".into(), "the output does not depend on it".into())),
        "{removed:?}"
    );
}

const PRUNE: &str = r#"style "prune"
param used: float = 0.5
param unused: float = 0.25
texture grain = noise(size: 64)
pass a: render(scene) {
  let spare = normal.world
  out c: rgba8unorm = vec4(used)
  out never_read: rgba8unorm = vec4(1.0)
}
pass dead: image(a) {
  out d: rgba8unorm = a.c * grain
}
pass b: image(a) {
  out c: rgba8unorm = a.c
}
output b.c
"#;

#[test]
fn prune_keeps_what_the_output_needs_and_says_why_it_drops_the_rest() {
    let (ir, graph) = front(PRUNE);
    let mut report = Report::default();
    let live = prune(&ir, &graph, &mut report);
    assert_eq!(live.passes, vec![pass_id(&ir, "a"), pass_id(&ir, "b")]);
    assert!(live.targets.contains(&target(&ir, "a", 0)));
    assert!(live.targets.contains(&target(&ir, "b", 0)));
    assert!(!live.targets.contains(&target(&ir, "a", 1)));
    assert_eq!(live.params.len(), 1);
    assert!(live.textures.is_empty());
    let removed = entries(&report, "removed");
    for (what, why) in [
        ("pass `dead`", "the output does not depend on it"),
        ("target `a.never_read`", "nothing reads it"),
        ("let `spare` in pass `a`", "no live output uses it"),
        ("param `unused`", "no live expression reads it"),
        ("texture `grain`", "no live expression reads it"),
    ] {
        assert!(
            removed.contains(&(what.to_string(), why.to_string())),
            "{what}: {why} missing from {removed:?}"
        );
    }
    assert_eq!(removed.len(), 5, "{removed:?}");
}

#[test]
fn prune_without_an_output_keeps_nothing() {
    let (mut ir, graph) = front(PRUNE);
    ir.output = None;
    let live = prune(&ir, &graph, &mut Report::default());
    assert!(live.passes.is_empty() && live.targets.is_empty());
}

// ------------------------------------------------------------- specialize

const BRANCH: &str = r#"style "branch"
param fancy: bool = false
pass base: render(scene) {
  out c: rgba8unorm = vec4(0.5)
}
pass extra: render(scene) {
  out c: rgba8unorm = vec4(normal.world, 1.0)
}
pass final: image(base, extra) {
  out c: rgba8unorm = if fancy { extra.c } else { base.c }
}
output final.c
"#;

/// Specialize, then prune again, as the pipeline does.
fn specialized(text: &str, keep_params: bool) -> (Ir, Vec<ParamBinding>, Live, Report) {
    let (mut ir, graph) = front(text);
    let live = prune(&ir, &graph, &mut Report::default());
    let mut report = Report::default();
    let bindings = npr_compiler::mid::specialize::specialize(&mut ir, &live, keep_params, &mut report);
    let graph = npr_compiler::mid::dag::build(&ir, &mut Vec::new());
    let live = prune(&ir, &graph, &mut report);
    (ir, bindings, live, report)
}

#[test]
fn a_folded_parameter_removes_the_branch_and_the_pass_only_it_read() {
    let (ir, bindings, live, report) = specialized(BRANCH, false);
    assert_eq!(bindings, vec![ParamBinding::Folded]);
    let out = ir.pass(pass_id(&ir, "final")).outputs[0].value;
    assert_eq!(
        ir.expr(out).kind,
        ExprKind::Target {
            target: target(&ir, "base", 0),
            copy: TargetCopy::This
        },
        "the else branch is left"
    );
    assert!(!live.passes.contains(&pass_id(&ir, "extra")));
    assert!(entries(&report, "removed").contains(&("pass `extra`".into(), "the output does not depend on it".into())));
    assert!(entries(&report, "folded").iter().any(|(w, _)| w == "param `fancy`"));
}

#[test]
fn a_kept_parameter_keeps_both_branches() {
    let (ir, bindings, live, _) = specialized(BRANCH, true);
    assert_eq!(bindings, vec![ParamBinding::Uniform]);
    let out = ir.pass(pass_id(&ir, "final")).outputs[0].value;
    assert!(matches!(ir.expr(out).kind, ExprKind::Select { .. }));
    assert!(live.passes.contains(&pass_id(&ir, "extra")));
}

#[test]
fn specializations_chain_to_the_cheapest_variant() {
    let text = r#"style "chain"
pass g: render(scene) {
  out pos: rgba32float = vec4(position.world, 1.0)
  out nrm: rgba32float = vec4(normal.world, 1.0)
}
pass err: image(g) {
  out e: rgba16float = lsa(g.pos, g.nrm, plane: false, aa: false)
}
output err.e
"#;
    let (ir, _, _, report) = specialized(text, false);
    let out = ir.pass(pass_id(&ir, "err")).outputs[0].value;
    let ExprKind::Call {
        callee: Callee::Operator(i),
        ..
    } = ir.expr(out).kind
    else {
        panic!("not an operator call: {:?}", ir.expr(out).kind);
    };
    assert_eq!(npr_stdlib::all()[i as usize].name, "lsa_curv");
    let special = entries(&report, "special");
    assert_eq!(special.len(), 2, "two steps: {special:?}");
    assert!(special[0].1.contains("calls `lsa_curv_aa` instead"), "{special:?}");
    assert!(special[1].1.contains("calls `lsa_curv` instead"), "{special:?}");
}

// --------------------------------------------------------------- allocate

fn allocated(text: &str) -> (Ir, Allocation, Report) {
    let (ir, graph) = front(text);
    let live = prune(&ir, &graph, &mut Report::default());
    let mut report = Report::default();
    let alloc = allocate(&ir, &live, &[], &mut report).expect("allocates");
    (ir, alloc, report)
}

fn physical(ir: &Ir, alloc: &Allocation, pass: &str) -> usize {
    let t = target(ir, pass, 0);
    alloc.targets.iter().find(|(x, _)| *x == t).expect("allocated").1
}

/// A chain a → b → c → d: each target is dead once the next pass has read it.
fn chain(formats: [&str; 4], scales: [&str; 4]) -> String {
    let mut s = format!(
        "style \"chain\"\npass a: render(scene) {} {{\n  out c: {} = vec4(normal.world, 1.0)\n}}\n",
        scales[0], formats[0]
    );
    for (i, (p, prev)) in [("b", "a"), ("c", "b"), ("d", "c")].iter().enumerate() {
        s += &format!(
            "pass {p}: image({prev}) {} {{\n  out c: {} = {prev}.c * 0.5\n}}\n",
            scales[i + 1],
            formats[i + 1]
        );
    }
    s + "output d.c\n"
}

#[test]
fn disjoint_lifetimes_share_a_physical_texture() {
    let (ir, alloc, report) = allocated(&chain(["rgba8unorm"; 4], [""; 4]));
    assert_eq!(alloc.physical.len(), 2, "{:?}", alloc.physical);
    assert_eq!(physical(&ir, &alloc, "a"), physical(&ir, &alloc, "c"));
    assert_eq!(physical(&ir, &alloc, "b"), physical(&ir, &alloc, "d"));
    assert_ne!(physical(&ir, &alloc, "a"), physical(&ir, &alloc, "b"));
    assert_eq!(entries(&report, "aliased").len(), 2);
}

#[test]
fn overlapping_lifetimes_do_not_share() {
    // `c` reads both `a` and `b`: `a` is still alive when `b` is written.
    let text = r#"style "overlap"
pass a: render(scene) {
  out c: rgba8unorm = vec4(1.0)
}
pass b: image(a) {
  out c: rgba8unorm = a.c * 0.5
}
pass c: image(a, b) {
  out c: rgba8unorm = a.c + b.c
}
output c.c
"#;
    let (ir, alloc, report) = allocated(text);
    assert_eq!(alloc.physical.len(), 3);
    let ids: std::collections::BTreeSet<usize> = ["a", "b", "c"].iter().map(|p| physical(&ir, &alloc, p)).collect();
    assert_eq!(ids.len(), 3);
    assert!(entries(&report, "aliased").is_empty());
}

/// The chain of [`chain`] where `a` also reads the previous frame of `c`,
/// which in this frame would alias `a`'s texture.
fn chain_with_history() -> String {
    chain(["rgba8unorm"; 4], [""; 4]).replacen(
        "out c: rgba8unorm = vec4(normal.world, 1.0)",
        "out c: rgba8unorm = vec4(normal.world, 1.0) + previous(c.c)",
        1,
    )
}

#[test]
fn a_history_target_is_never_aliased() {
    let (ir, alloc, _) = allocated(&chain_with_history());
    let c = physical(&ir, &alloc, "c");
    assert!(alloc.physical[c].history, "{:?}", alloc.physical);
    for other in ["a", "b", "d"] {
        assert_ne!(physical(&ir, &alloc, other), c, "`{other}` shares the history texture");
        assert!(!alloc.physical[physical(&ir, &alloc, other)].history);
    }
    assert_eq!(alloc.physical.iter().filter(|p| p.history).count(), 1);
}

#[test]
fn a_target_read_only_by_an_earlier_pass_through_previous_stays_live() {
    // `e` runs after `a`, and only `a` reads it, through `previous(...)`.
    let text = r#"style "echo"
pass a: image() {
  out c: rgba8unorm = previous(e.c) * 0.5
}
pass e: image(a) {
  out c: rgba8unorm = a.c + vec4(0.1)
}
output a.c
"#;
    let (ir, graph) = front(text);
    let mut report = Report::default();
    let live = prune(&ir, &graph, &mut report);
    assert!(live.passes.contains(&pass_id(&ir, "e")), "{:?}", report.entries);
    assert!(live.history.contains(&target(&ir, "e", 0)));
    assert!(entries(&report, "removed").is_empty(), "{:?}", report.entries);
    // Within the frame `a` still runs first: a previous read is no dependency.
    assert_eq!(graph.order, vec![pass_id(&ir, "a"), pass_id(&ir, "e")]);
}

#[test]
fn aliasing_needs_the_same_format_and_scale() {
    let (_, formats, _) = allocated(&chain(
        ["rgba8unorm", "rgba8unorm", "rgba16float", "rgba8unorm"],
        [""; 4],
    ));
    // `c` cannot take `a`'s rgba8unorm texture; `d` takes `b`'s.
    assert_eq!(formats.physical.len(), 3, "{:?}", formats.physical);
    let (_, scales, _) = allocated(&chain(["rgba8unorm"; 4], ["", "", "scale 1/2", ""]));
    assert_eq!(scales.physical.len(), 3, "{:?}", scales.physical);
}

#[test]
fn a_live_target_without_a_reader_is_an_internal_error() {
    let (mut ir, graph) = front(&chain(["rgba8unorm"; 4], [""; 4]));
    let mut live = prune(&ir, &graph, &mut Report::default());
    // An impossible state: prune never keeps a target that nothing reads.
    let a = pass_id(&ir, "a");
    let copy = ir.passes[a.0 as usize].outputs[0].clone();
    ir.passes[a.0 as usize].outputs.push(PassOutput {
        name: "stray".into(),
        ..copy
    });
    live.targets.insert(TargetRef { pass: a, output: 1 });
    let err = allocate(&ir, &live, &[], &mut Report::default()).expect_err("internal error");
    assert!(err.message.contains("`a.stray` has no reader"), "{}", err.message);
    assert_eq!(err.to_diagnostic().code, npr_diag::codes::INTERNAL);
}

#[test]
fn an_output_without_a_target_is_an_internal_error() {
    let (ir, graph) = front(&chain(["rgba8unorm"; 4], [""; 4]));
    let live = prune(&ir, &graph, &mut Report::default());
    let mut alloc = allocate(&ir, &live, &[], &mut Report::default()).expect("allocates");
    // An impossible state: the allocator always gives the output a target.
    let out = ir.output.expect("output");
    alloc.targets.retain(|(t, _)| *t != out);
    let err = npr_compiler::back::emit::manifest::build(
        &ir,
        &live,
        &alloc,
        &[],
        &[],
        &SourceMap::new(),
        "t.npr",
        &Default::default(),
    )
    .expect_err("internal error");
    assert!(err.message.contains("output"), "{}", err.message);
    assert!(err.detail.contains("`d.c`"), "{}", err.detail);
    assert_eq!(err.to_diagnostic().code, npr_diag::codes::INTERNAL);
}

// ---------------------------------------------------------------- compute

const COMPUTE: &str = r#"style "compute"
pass sums: compute(vertices) {
  reduce n: float = sum(1.0)
  reduce unread: vec3 = sum(position)
  reduce c: vec2 = sum(project(position).xy)
}
pass follow: compute(objects) {
  state o: vec2 = vec2(0.0)
  state idle: float = 0.0
  o = o + sums.c / max(sums.n, 1.0)
  idle = idle + 1.0
  out k: float = o.x
}
pass spare: compute(objects) {
  out z: float = sums.n
}
pass shade: render(scene) {
  out c: r32float = follow.k
}
output shade.c
"#;

#[test]
fn prune_keeps_the_values_a_live_pass_reads_and_the_states_they_read() {
    let (ir, graph) = front(COMPUTE);
    let mut report = Report::default();
    let live = prune(&ir, &graph, &mut report);
    let (sums, follow) = (pass_id(&ir, "sums"), pass_id(&ir, "follow"));
    // `follow.k` reads state `o` (slot 2 after k), which reads sums.c and sums.n;
    // `idle` and `sums.unread` are read by nothing; `spare` by no live pass.
    assert_eq!(live.value_slots(follow), vec![0, 1]);
    assert_eq!(live.value_slots(sums), vec![0, 2]);
    assert!(!live.passes.contains(&pass_id(&ir, "spare")));
    let removed = entries(&report, "removed");
    for what in ["value `sums.unread`", "value `follow.idle`", "pass `spare`"] {
        assert!(
            removed.iter().any(|(w, _)| w == what),
            "{what} not reported: {removed:?}"
        );
    }
    let warnings = npr_compiler::mid::prune::unread_compute_passes(&ir, &live);
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].message.contains("`spare`"));
}

#[test]
fn allocate_packs_live_values_and_gives_state_a_written_flag() {
    let (ir, alloc, report) = allocated(COMPUTE);
    let (sums, follow) = (pass_id(&ir, "sums"), pass_id(&ir, "follow"));
    // sums: n and c packed into slots 0 and 1 (unread dropped); no state.
    assert_eq!(alloc.value_slots.get(&(sums, 0)), Some(&0));
    assert_eq!(alloc.value_slots.get(&(sums, 2)), Some(&1));
    assert_eq!(alloc.value_slots.get(&(sums, 1)), None);
    assert_eq!(alloc.slots_per_object[&sums], 2);
    assert!(!alloc.keeps_state(&ir, sums));
    // follow: k, o, and the flag.
    assert_eq!(alloc.slots_per_object[&follow], 3);
    assert!(alloc.keeps_state(&ir, follow));
    assert_eq!(alloc.pass_index(follow), Some(1));
    let buffers = entries(&report, "buffer");
    assert!(
        buffers
            .iter()
            .any(|(w, why)| w == "compute pass `follow`" && why.contains("keeps state")),
        "{buffers:?}"
    );
}
