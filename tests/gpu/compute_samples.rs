//! Compute passes over stratified surface samples (`compute(samples)`,
//! Breslav et al. 2007 §3.1) on the real runner: per-object sums of the
//! samples' world positions, normals and spacing against the same samples
//! drawn on the CPU and transformed in f64; the count and seed settings.

use glam::DVec3;
use npr_runner::scene::samples::{object_seed, stratified};
use npr_runner::scene::Scene;
use npr_runner::{FrameSpec, Renderer, StyleProgram};

use crate::common;
use common::{gpu, root};

fn program(text: &str) -> StyleProgram {
    common::compile_text(text)
}

fn scene(path: &str) -> Scene {
    let mut sources = npr_diag::SourceMap::new();
    npr_runner::scene::load_scene(&root().join(path), &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)))
}

const STYLE: &str = r#"style "Samples"
pass sums: compute(samples) {
  count: 300
  seed: 5
  reduce n: float = sum(1.0)
  reduce p: vec3 = sum(position)
  reduce normal_sum: vec3 = sum(normal)
  reduce h: float = max(sample.spacing)
}
pass shade: render(scene) {
  out c: rgba32float = vec4(sums.p + sums.normal_sum, sums.n + sums.h)
}
output shade.c
"#;

#[test]
fn sample_sums_match_the_same_samples_in_f64() {
    let program = program(STYLE);
    let scene = scene("examples/scenes/spheres.toml");
    let mut r = Renderer::new(&gpu().device, &gpu().queue, &program, &scene).expect("renderer");
    r.render(&scene, &FrameSpec::still(16, 16, 0)).expect("frame");
    let got = r.read_object_values("sums").expect("values");
    for (o, object) in scene.objects.iter().enumerate() {
        let mesh = &object.mesh;
        let drawn = stratified(mesh, 300, object_seed(5, o));
        assert!(
            drawn.samples.len().abs_diff(300) <= 30,
            "object {o}: {} samples",
            drawn.samples.len()
        );
        let model = object.model.as_dmat4();
        let normal_matrix = model.inverse().transpose();
        let (mut p, mut n) = (DVec3::ZERO, DVec3::ZERO);
        for s in &drawn.samples {
            let at = |a: &[[f32; 3]]| npr_lab::patterns_f64::at_sample(a, s);
            p += model.transform_point3(at(&mesh.positions));
            n += normal_matrix.transform_vector3(at(&mesh.normals));
        }
        let g = &got[o];
        assert_eq!(g[0][0] as usize, drawn.samples.len(), "object {o} sample count");
        let scale = drawn.samples.len() as f64 * 10.0;
        for k in 0..3 {
            assert!(
                (g[1][k] as f64 - p[k]).abs() <= 1e-5 * scale,
                "object {o} Σ position[{k}]: {} vs {}",
                g[1][k],
                p[k]
            );
            assert!(
                (g[2][k] as f64 - n[k]).abs() <= 1e-5 * scale,
                "object {o} Σ normal[{k}]: {} vs {}",
                g[2][k],
                n[k]
            );
        }
        // The spacing in world units: the object-space spacing times the
        // model's mean linear scale.
        let det = object.model.as_dmat4().determinant().abs();
        let want = drawn.spacing as f64 * det.cbrt();
        assert!(
            (g[3][0] as f64 - want).abs() <= 1e-5 * want,
            "object {o} spacing {} vs {want}",
            g[3][0]
        );
    }
}

#[test]
fn a_sample_count_that_is_not_a_whole_number_is_refused() {
    let mut sources = npr_diag::SourceMap::new();
    let text = STYLE.replace("count: 300", "count: 2.5");
    match npr_compiler::compile_source("c.npr", &text, root(), &mut sources, &Default::default()) {
        Err(npr_compiler::CompileError::User(d)) => {
            let r = npr_diag::diagnostic::render(&d, &sources, false);
            assert!(r.contains("E0203") && r.contains("whole number"), "{r}");
        }
        other => panic!("expected E0203, got {:?}", other.map(|_| ())),
    }
}
