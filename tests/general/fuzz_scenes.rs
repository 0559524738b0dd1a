//! Property test: mutated scenes and mesh files never panic the scene
//! reader (issue 13). Seeds are every scene in `examples/scenes/` and every
//! OBJ in `examples/models/`; mutations splice TOML or OBJ tokens (keys of
//! every table, numbers that are not finite, huge or negative indices),
//! and the glTF files of `runner/tests/data/` (skinned and morphing; a
//! textured material with a `data:` image) their JSON tokens,
//! delete runs and truncate. A scene either loads or gets diagnostics whose
//! spans lie inside the file; a mesh either loads or gets a `MeshLoadError`
//! with a code. `NPR_FUZZ_CASES` sets the count for a soak run.

use crate::common;

use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples")
}

fn read_all(dir: &Path, ext: &str, at_least: usize) -> Vec<(String, String)> {
    let files = common::fuzz::files_with_extension(dir, ext);
    assert!(
        files.len() >= at_least,
        "expected every {ext} in {} as a seed",
        dir.display()
    );
    files
        .into_iter()
        .map(|p| {
            (
                p.display().to_string(),
                std::fs::read_to_string(&p).expect("readable seed"),
            )
        })
        .collect()
}

fn scene_seeds() -> &'static [(String, String)] {
    static S: OnceLock<Vec<(String, String)>> = OnceLock::new();
    S.get_or_init(|| read_all(&examples().join("scenes"), "toml", 8))
}

/// OBJ seeds, each cut to its first 400 lines (mutations near the start
/// matter as much, and whole meshes would make each case slow).
fn obj_seeds() -> &'static [(String, String)] {
    static S: OnceLock<Vec<(String, String)>> = OnceLock::new();
    S.get_or_init(|| {
        read_all(&examples().join("models"), "obj", 3)
            .into_iter()
            .map(|(n, t)| (n, t.lines().take(400).collect::<Vec<_>>().join("\n")))
            .collect()
    })
}

const TOML_TOKENS: &[&str] = &[
    "[",
    "]",
    "[[",
    "]]",
    "{",
    "}",
    "=",
    ",",
    "\"",
    "'",
    "#",
    "\n",
    ".",
    "0",
    "1",
    "-1",
    "1e39",
    "-1e39",
    "nan",
    "inf",
    "-inf",
    "0.0",
    "3.5",
    "1e-30",
    "true",
    "false",
    "\"x.obj\"",
    "\"../models/spot.obj\"",
    "\"missing.png\"",
    "\"#ff0000\"",
    "\"#zz\"",
    "[0.0, 0.0]",
    "[1.0, 2.0, 3.0]",
    "[nan, 0.0, 0.0]",
    "[]",
    "{ kind = \"sphere\" }",
    "{ kind = \"ocean\" }",
    "{ kind = \"plane\", size = -1.0 }",
    "[camera]",
    "[light]",
    "[light2]",
    "[[object]]",
    "[[camera.keys]]",
    "position",
    "target",
    "up",
    "fov",
    "near",
    "far",
    "stereo",
    "eye_separation",
    "keys",
    "time",
    "direction",
    "color",
    "intensity",
    "name",
    "mesh",
    "primitive",
    "kind",
    "sphere",
    "cube",
    "plane",
    "torus",
    "ocean",
    "scale",
    "rotate",
    "translate",
    "tags",
    "params",
    "crease_angle",
    "patches",
    "blend_rings",
    "\"parts\"",
    "spin",
    "background",
    "segments",
    "1000000000",
    "4294967296",
    "animation",
    "{ clip = \"bend\" }",
    "{ clip = \"bend\", speed = nan, loop = false, offset = -1e39 }",
    "clip",
];

/// glTF JSON tokens: keys of skins, morph targets and animations, and
/// indices and numbers that point nowhere or are not finite.
const GLTF_TOKENS: &[&str] = &[
    "{",
    "}",
    "[",
    "]",
    ",",
    ":",
    "\"",
    "0",
    "1",
    "2",
    "3",
    "7",
    "9",
    "10",
    "-1",
    "99",
    "4294967296",
    "1e39",
    "0.5",
    "null",
    "\"joints\"",
    "\"skin\"",
    "\"weights\"",
    "\"WEIGHTS_0\"",
    "\"JOINTS_0\"",
    "\"targets\"",
    "\"inverseBindMatrices\"",
    "\"children\"",
    "\"input\"",
    "\"output\"",
    "\"node\"",
    "\"path\"",
    "\"rotation\"",
    "\"translation\"",
    "\"scale\"",
    "\"CUBICSPLINE\"",
    "\"STEP\"",
    "\"count\"",
    "\"byteOffset\"",
];

/// Skinned and morphing glTF seeds (JSON with an embedded buffer).
fn gltf_seeds() -> &'static [(String, String)] {
    static S: OnceLock<Vec<(String, String)>> = OnceLock::new();
    S.get_or_init(|| {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("runner/tests/data");
        read_all(&dir, "gltf", 1)
    })
}

const OBJ_TOKENS: &[&str] = &[
    "v",
    "vt",
    "vn",
    "f",
    "o",
    "g",
    "s",
    "usemtl",
    "mtllib x.mtl",
    "#",
    "\n",
    " ",
    "/",
    "//",
    "0",
    "1",
    "-1",
    "2",
    "-2",
    "99999999",
    "-99999999",
    "4294967296",
    "nan",
    "inf",
    "-inf",
    "1e39",
    "0.5",
    "1/1/1",
    "1//1",
    "-1/-1/-1",
    "f 1 2",
    "f 1 2 3 4 5 6",
    "v 0 0",
    "vt 0",
    "vn 0 0",
];

/// Apply `edits` (position, kind, token) to `text`: delete 1–12 bytes,
/// insert a token, insert a token and a space, or truncate.
fn mutate(text: &str, edits: &[(u32, u8, prop::sample::Index)], tokens: &[&str]) -> String {
    let mut text = text.to_string();
    for (pos, kind, tok) in edits {
        let mut at = *pos as usize % (text.len() + 1);
        while !text.is_char_boundary(at) {
            at -= 1;
        }
        let token = tok.get(tokens);
        match kind {
            0 => {
                let mut end = (at + 1 + *pos as usize % 12).min(text.len());
                while !text.is_char_boundary(end) {
                    end -= 1;
                }
                text.replace_range(at..end, "");
            }
            1 => text.insert_str(at, token),
            2 => {
                text.insert(at, ' ');
                text.insert_str(at, token);
            }
            _ => text.truncate(at),
        }
    }
    text
}

/// A scratch file per test thread (cases run one at a time per thread).
fn scratch_file(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz-scenes");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir.join(format!("{name}-{:?}", std::thread::current().id()).replace(['(', ')'], ""))
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: common::fuzz::cases(200),
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x7363_656e),
        ..ProptestConfig::default()
    })]

    #[test]
    fn mutated_scenes_never_panic(
        seed in any::<prop::sample::Index>(),
        edits in prop::collection::vec((any::<u32>(), 0u8..4, any::<prop::sample::Index>()), 1..8),
    ) {
        let (_, text) = seed.get(scene_seeds());
        let text = mutate(text, &edits, TOML_TOKENS);
        let mut sources = npr_diag::SourceMap::new();
        let file = sources.add("fuzz.toml", text.clone());
        // Relative meshes and images resolve against examples/scenes, as the seeds' do.
        match npr_runner::scene::parse_scene(&text, file, &examples().join("scenes")) {
            Ok(scene) => prop_assert!(scene.objects.len() < 1_000_000),
            Err(diags) => {
                prop_assert!(!diags.is_empty());
                for d in &diags {
                    prop_assert!(npr_diag::codes::ALL.iter().any(|(c, _)| *c == d.code), "unknown code {}", d.code);
                    for l in &d.labels {
                        prop_assert!(l.span.start <= l.span.end && l.span.end as usize <= text.len(), "{d:?}");
                    }
                }
                let _ = npr_diag::diagnostic::render(&diags, &sources, false);
            }
        }
    }

    #[test]
    fn mutated_obj_files_never_panic(
        seed in any::<prop::sample::Index>(),
        edits in prop::collection::vec((any::<u32>(), 0u8..4, any::<prop::sample::Index>()), 1..8),
    ) {
        let (_, text) = seed.get(obj_seeds());
        let text = mutate(text, &edits, OBJ_TOKENS);
        let path = scratch_file("mesh.obj");
        let path = path.with_extension("obj");
        std::fs::write(&path, &text).expect("write mesh");
        match npr_runner::scene::load_mesh_file(&path) {
            Ok(mesh) => {
                // Every index the renderer will draw names a vertex.
                let n = mesh.positions.len() as u32;
                prop_assert!(mesh.indices.iter().all(|i| *i < n), "an index past {n} vertices");
            }
            Err(e) => prop_assert!(npr_diag::codes::ALL.iter().any(|(c, _)| *c == e.code), "code {}", e.code),
        }
    }

    #[test]
    fn mutated_skinned_gltf_files_never_panic(
        seed in any::<prop::sample::Index>(),
        edits in prop::collection::vec((any::<u32>(), 0u8..4, any::<prop::sample::Index>()), 1..6),
    ) {
        let (_, text) = seed.get(gltf_seeds());
        let text = mutate(text, &edits, GLTF_TOKENS);
        let path = scratch_file("rig").with_extension("gltf");
        std::fs::write(&path, &text).expect("write mesh");
        match npr_runner::scene::load_mesh_and_rig(&path) {
            Ok((mesh, rig)) => {
                let n = mesh.positions.len() as u32;
                prop_assert!(mesh.indices.iter().all(|i| *i < n), "an index past {n} vertices");
                // Every clip poses and deforms, at and between its keys and past them.
                if let Some(rig) = rig {
                    for clip in 0..rig.clips.len() {
                        for t in [-1.0f32, 0.0, 0.5, 1.0, 1e6] {
                            let posed = rig.deform(&rig.pose(Some((clip, t))));
                            prop_assert_eq!(posed.positions.len(), mesh.positions.len());
                        }
                    }
                }
            }
            Err(e) => prop_assert!(npr_diag::codes::ALL.iter().any(|(c, _)| *c == e.code), "code {}", e.code),
        }
    }
}
