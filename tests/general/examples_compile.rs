//! Every example style compiles; its WGSL and manifest are snapshot-tested,
//! and naga parses and validates every emitted module.

use npr_compiler::CompileOptions;
use npr_diag::SourceMap;
use std::path::{Path, PathBuf};

/// The example styles: `examples/*.npr`, and `examples/post/*.npr`, the
/// styles over a host's inputs.
fn examples() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = ["examples", "examples/post"]
        .iter()
        .flat_map(|d| std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(d)).expect("examples dir"))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "npr"))
        .collect();
    v.sort();
    assert!(v.len() >= 3, "expected at least three examples, found {v:?}");
    v
}

fn compile(path: &Path, keep_params: bool) -> npr_compiler::Compiled {
    let mut sources = SourceMap::new();
    match npr_compiler::compile_file(
        path,
        &mut sources,
        &CompileOptions {
            keep_params,
            dump_ir: false,
            scene: None,
            settings: Vec::new(),
            schedule: npr_compiler::schedule::Schedule::Naive,
            tile_apron_deficit: 0,
            // Every example keeps to the default paths policy.
            paths: Some(
                npr_diag::paths::PathPolicy::new(&npr_diag::paths::PathPolicy::default_root(&[path]), &[])
                    .expect("root"),
            ),
            files: Default::default(),
        },
    ) {
        Ok(c) => c,
        Err(npr_compiler::CompileError::User(d)) => panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)),
        Err(npr_compiler::CompileError::Internal(e)) => panic!("{e}\n{}", e.wgsl.clone().unwrap_or_default()),
    }
}

#[test]
fn every_example_compiles_and_validates_with_naga() {
    for path in examples() {
        for keep in [false, true] {
            let c = compile(&path, keep);
            assert!(!c.shaders.is_empty(), "{}", path.display());
            for (file, wgsl) in &c.shaders {
                let module = naga::front::wgsl::parse_str(wgsl)
                    .unwrap_or_else(|e| panic!("{}: {file}: {}", path.display(), e.emit_to_string(wgsl)));
                naga::valid::Validator::new(
                    naga::valid::ValidationFlags::all(),
                    naga::valid::Capabilities::default(),
                )
                .validate(&module)
                .unwrap_or_else(|e| panic!("{}: {file}: {}", path.display(), e.emit_to_string(wgsl)));
                // Every entry point the manifest names exists, in its stage.
                let pass = c
                    .manifest
                    .passes
                    .iter()
                    .find(|p| p.shader == *file)
                    .expect("a pass per shader");
                for (field, entry) in pass.kind.entries() {
                    let stage = match field {
                        "vertex_entry" => naga::ShaderStage::Vertex,
                        "fragment_entry" => naga::ShaderStage::Fragment,
                        _ => naga::ShaderStage::Compute,
                    };
                    assert!(
                        module.entry_points.iter().any(|e| e.name == entry && e.stage == stage),
                        "{}: {file}: no {stage:?} entry `{entry}`",
                        path.display()
                    );
                }
            }
        }
    }
}

/// Absolute paths differ between machines: each texture's file and each
/// art-map filter's source as written.
fn relative_paths(manifest: &mut npr_abi::Manifest) {
    for t in &mut manifest.textures {
        match &mut t.source {
            npr_abi::manifest::TextureSourceManifest::Image { resolved, path, .. } => *resolved = path.clone(),
            npr_abi::manifest::TextureSourceManifest::Artmap(spec) => {
                spec.resolved = spec.path.clone();
                spec.filter.manifest.source = spec.filter.path.clone();
                relative_paths(&mut spec.filter.manifest);
            }
            _ => {}
        }
    }
}

#[test]
fn compile_snapshots() {
    for path in examples() {
        let c = compile(&path, false);
        let name = path.file_stem().unwrap_or_default().to_string_lossy().into_owned();
        let mut manifest = c.manifest.clone();
        // Absolute paths differ between machines.
        manifest.source = path
            .strip_prefix(env!("CARGO_MANIFEST_DIR"))
            .expect("under the repository")
            .display()
            .to_string();
        relative_paths(&mut manifest);
        insta::assert_json_snapshot!(format!("{name}__manifest"), manifest);
        for (file, wgsl) in &c.shaders {
            insta::assert_snapshot!(format!("{name}__{file}"), wgsl);
        }
        insta::assert_snapshot!(format!("{name}__report"), c.report.render());
    }
}

#[test]
fn skew_zero_emits_no_8_tap_code() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/metatexture.npr");
    let folded = compile(&path, false);
    let wgsl = folded.shader("shade.wgsl").expect("shade pass");
    assert!(wgsl.contains("npr_metatexture4("), "4-tap path used");
    assert!(
        !wgsl.contains("fn npr_metatexture_grad("),
        "no 8-tap code when skew_levels = 0:\n{wgsl}"
    );
    assert!(folded.report.render().contains("calls `metatexture4` instead"));
    // With skew_levels kept as a uniform (or set ≥ 1) the 8-tap path is emitted.
    let kept = compile(&path, true);
    assert!(kept
        .shader("shade.wgsl")
        .expect("shade")
        .contains("fn npr_metatexture_grad("));
    let text = std::fs::read_to_string(&path)
        .expect("read")
        .replace("skew_levels: int = 0", "skew_levels: int = 2");
    let mut sources = SourceMap::new();
    let skewed = npr_compiler::compile_source(
        "skew.npr",
        &text,
        path.parent().expect("dir"),
        &mut sources,
        &CompileOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e:?}"));
    assert!(skewed
        .shader("shade.wgsl")
        .expect("shade")
        .contains("fn npr_metatexture_grad("));
}

/// `examples/lsa_contours.npr` with some of its parameter defaults replaced.
fn compile_lsa_variant(replacements: &[(&str, &str)]) -> npr_compiler::Compiled {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/lsa_contours.npr");
    let mut text = std::fs::read_to_string(&path).expect("read");
    for (from, to) in replacements {
        assert!(text.contains(from), "{from} not in lsa_contours.npr");
        text = text.replace(from, to);
    }
    let mut sources = SourceMap::new();
    npr_compiler::compile_source(
        "lsa_variant.npr",
        &text,
        path.parent().expect("dir"),
        &mut sources,
        &CompileOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e:?}"))
}

#[test]
fn disabled_lsa_extensions_compile_away() {
    const PLANE_OFF: (&str, &str) = ("param plane: bool = true", "param plane: bool = false");
    const AA_OFF: (&str, &str) = ("param aa: bool = true", "param aa: bool = false");
    // Markers of each extension's code in the emitted WGSL.
    let plane_code = "fn npr_lsa_plane__den(";
    let aa_code = "fn npr_lsa_aa__mix(";
    let has = |c: &npr_compiler::Compiled, s: &str| c.shader("error.wgsl").expect("error pass").contains(s);

    let full = compile_lsa_variant(&[]);
    assert!(has(&full, "fn npr_lsa(") && has(&full, plane_code) && has(&full, aa_code));

    let no_plane = compile_lsa_variant(&[PLANE_OFF]);
    assert!(has(&no_plane, "fn npr_lsa_curv_aa(") && !has(&no_plane, plane_code) && has(&no_plane, aa_code));

    let no_aa = compile_lsa_variant(&[AA_OFF]);
    assert!(has(&no_aa, "fn npr_lsa_sum(") && has(&no_aa, plane_code));
    assert!(!has(&no_aa, "px + 2 * m"), "no two-step loads without eq. 8");

    // Both off: the specializations chain down to the base operator.
    let base = compile_lsa_variant(&[PLANE_OFF, AA_OFF]);
    assert!(has(&base, "fn npr_lsa_curv(") && !has(&base, plane_code) && !has(&base, aa_code));
    assert!(!has(&base, "fn npr_lsa("), "the general operator is not emitted");
    assert!(base.report.render().contains("calls `lsa_curv` instead"));
    insta::assert_snapshot!(
        "lsa_contours_both_extensions_off__error",
        base.shader("error.wgsl").expect("error pass")
    );

    // Kept as uniforms (e.g. for a live editor), both extensions stay switchable at run time.
    let kept = compile(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/lsa_contours.npr"),
        true,
    );
    assert!(has(&kept, "fn npr_lsa(") && has(&kept, plane_code) && has(&kept, aa_code));
}
