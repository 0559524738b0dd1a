//! A target read as a value several times in one pass is loaded once: the
//! emitter names every repeated value read of a (target, eye) pair, whether
//! the reads share a `let` (`let e = g.e` then `e.x`, `e.y`) or are separate
//! expressions (`g.d.x + g.d.y`).

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use std::path::Path;

const STYLE: &str = r#"style "shared reads"
pass g: render(scene) {
  out e: rgba16float = vec4(normal.world, 1.0)
  out d: rgba16float = vec4(position.world, 1.0)
  out f: r32float = depth
}
pass ink: image(g) {
  let e = g.e
  let line = max(max(e.x, e.y), max(e.z, e.w))
  out c: rgba8unorm = vec4(vec3(line + g.d.x * g.d.y + g.f), 1.0)
}
output ink.c
"#;

#[test]
fn each_target_is_loaded_once_per_pass() {
    let mut sources = SourceMap::new();
    let c = npr_compiler::compile_source(
        "shared.npr",
        STYLE,
        Path::new("."),
        &mut sources,
        &CompileOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e:?}"));
    let wgsl = c.shader("ink.wgsl").expect("ink pass");
    for t in ["t_g_e", "t_g_d", "t_g_f"] {
        assert_eq!(
            wgsl.matches(&format!("npr_load({t}, ")).count(),
            1,
            "{t} loaded once:\n{wgsl}"
        );
    }
    let fs = &wgsl[wgsl.find("@fragment").expect("fragment shader")..];
    insta::assert_snapshot!("shared_target_reads", fs);
}
