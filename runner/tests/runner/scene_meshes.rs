//! Mesh files through scenes: the real OBJ models (spot with UVs, cow
//! without), attribute checks, transforms, params, and glTF/GLB round trips
//! with generated assets.

use glam::{Mat4, Vec3};
use npr_runner::scene::{load_scene, parse_scene, Attribute, Mesh, Scene};
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

fn models_dir() -> PathBuf {
    // Copies of the shared test assets inside the repository, so a clean
    // clone (CI) has them.
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/models")
}

fn load_spot_cow() -> (Scene, npr_diag::SourceMap) {
    let mut sources = npr_diag::SourceMap::new();
    match load_scene(&data_dir().join("scene_spot_cow.toml"), &mut sources) {
        Ok(scene) => (scene, sources),
        Err(diagnostics) => panic!("{}", npr_diag::diagnostic::render(&diagnostics, &sources, false)),
    }
}

fn object<'s>(scene: &'s Scene, name: &str) -> &'s npr_runner::scene::Object {
    scene
        .objects
        .iter()
        .find(|o| o.name == name)
        .unwrap_or_else(|| panic!("no object `{name}`"))
}

fn assert_sound_attributes(mesh: &Mesh) {
    assert!(mesh.validate().is_ok(), "{}", mesh.source);
    for n in &mesh.normals {
        let length = Vec3::from_array(*n).length();
        assert!((length - 1.0).abs() < 1e-5, "{}: normal {n:?}", mesh.source);
    }
    if let Some(tangents) = &mesh.tangents {
        for (t, n) in tangents.iter().zip(&mesh.normals) {
            let t3 = Vec3::new(t[0], t[1], t[2]);
            assert!((t3.length() - 1.0).abs() < 1e-5, "{}: tangent {t:?}", mesh.source);
            assert!(
                t3.dot(Vec3::from_array(*n)).abs() < 1e-5,
                "{}: tangent {t:?} vs normal {n:?}",
                mesh.source
            );
            assert!(t[3] == 1.0 || t[3] == -1.0);
        }
    }
}

/// On a closed, consistently wound mesh, the smooth normals point away from
/// the centroid almost everywhere.
fn fraction_facing_outwards(mesh: &Mesh) -> f32 {
    let centroid: Vec3 =
        mesh.positions.iter().map(|p| Vec3::from_array(*p)).sum::<Vec3>() / mesh.positions.len() as f32;
    let outwards = mesh
        .positions
        .iter()
        .zip(&mesh.normals)
        .filter(|(p, n)| (Vec3::from_array(**p) - centroid).dot(Vec3::from_array(**n)) > 0.0)
        .count();
    outwards as f32 / mesh.positions.len() as f32
}

#[test]
fn spot_has_uvs_and_derived_tangents() {
    let (scene, _) = load_spot_cow();
    let spot = &object(&scene, "spot").mesh;
    assert_eq!(spot.triangle_count(), 5856);
    assert!(spot.source.ends_with("spot.obj"));
    let uvs = spot.uvs.as_ref().expect("spot.obj has vt lines");
    // spot.obj's own `vt` stray up to 0.053 outside [0, 1]; they are kept.
    assert!(uvs.iter().flatten().all(|c| (-0.06..=1.06).contains(c)));
    // The flip to top-left origin: the file's v = 1.00065 becomes -0.00065.
    assert!(uvs.iter().any(|uv| (uv[1] + 0.00065).abs() < 1e-6));
    assert!(spot.tangents.is_some());
    assert_sound_attributes(spot);
    assert!(
        fraction_facing_outwards(spot) > 0.8,
        "{}",
        fraction_facing_outwards(spot)
    );
}

#[test]
fn spot_normals_are_welded_across_uv_seams() {
    let (scene, _) = load_spot_cow();
    let spot = &object(&scene, "spot").mesh;
    let mut by_position: std::collections::HashMap<[u32; 3], [f32; 3]> = Default::default();
    let mut duplicated = 0;
    for (p, n) in spot.positions.iter().zip(&spot.normals) {
        let key = p.map(f32::to_bits);
        if let Some(first) = by_position.insert(key, *n) {
            duplicated += 1;
            assert_eq!(first, *n, "seam vertex at {p:?} has two normals");
        }
    }
    // Single indexing split spot along its UV seams.
    assert!(duplicated > 0);
}

#[test]
fn cow_has_computed_normals_and_no_uvs() {
    let (scene, _) = load_spot_cow();
    let cow = &object(&scene, "cow").mesh;
    assert_eq!(cow.triangle_count(), 5804);
    assert_eq!(cow.vertex_count(), 2903);
    assert!(cow.uvs.is_none() && cow.tangents.is_none());
    assert!(!cow.has(Attribute::Uv) && !cow.has(Attribute::Tangent));
    assert_sound_attributes(cow);
    assert!(fraction_facing_outwards(cow) > 0.7, "{}", fraction_facing_outwards(cow));
}

#[test]
fn coordinates_are_kept_as_in_the_file() {
    let (scene, _) = load_spot_cow();
    let cow = &object(&scene, "cow").mesh;
    // The first `v` line of cow.obj.
    assert!(cow.positions.contains(&[2.292449, -0.871852, -0.8824]));
}

#[test]
fn check_attributes_flags_only_the_cow() {
    let (scene, sources) = load_spot_cow();
    let diagnostics = scene.check_attributes(&[Attribute::Uv], "the style `hatching` reads `uv`");
    assert_eq!(diagnostics.len(), 1, "{diagnostics:#?}");
    let diagnostic = &diagnostics[0];
    assert_eq!(diagnostic.code, npr_diag::codes::MISSING_ATTRIBUTE);
    let span = diagnostic.primary_span().expect("points at the mesh");
    assert_eq!(sources.snippet(span), "\"../../../examples/models/cow.obj\"");
    assert!(diagnostic.message.contains("the style `hatching` reads `uv`") && diagnostic.message.contains("`cow`"));
    let help = diagnostic.help.as_deref().unwrap_or_default();
    assert!(help.contains("spot.obj has UVs; cow.obj does not"), "{help}");
    assert!(help.contains("use a primitive"), "{help}");
    let rendered = npr_diag::diagnostic::render(&diagnostics, &sources, false);
    assert!(rendered.contains("E0403") && rendered.contains("cow.obj"), "{rendered}");

    // Tangents come with UVs, so the same object lacks them.
    assert_eq!(
        scene
            .check_attributes(&[Attribute::Tangent], "normal mapping needs tangents")
            .len(),
        1
    );
    assert_eq!(
        scene.check_attributes(&[Attribute::Uv, Attribute::Tangent], "x").len(),
        1
    );
    assert!(scene
        .check_attributes(&[Attribute::Position, Attribute::Normal], "x")
        .is_empty());
}

#[test]
fn the_scene_file_sets_light_background_transforms_and_params() {
    let (scene, sources) = load_spot_cow();
    assert_eq!(scene.objects.len(), 3);
    assert_eq!(scene.background, [32.0 / 255.0, 32.0 / 255.0, 32.0 / 255.0, 1.0]);
    assert!((scene.light.direction - Vec3::new(0.5, 1.0, 0.8).normalize()).length() < 1e-6);
    assert_eq!((scene.light.color, scene.light.intensity), ([1.0; 3], 2.0));

    let spot = object(&scene, "spot");
    assert_eq!(spot.tags, ["hero", "caster"]);
    assert!(spot.casts_shadows && spot.has_tag("hero"));
    // Rotated 90° about Y: +X goes to -Z.
    assert!((spot.model.transform_vector3(Vec3::X) - Vec3::NEG_Z).length() < 1e-6);
    assert_eq!(spot.params["tint"], vec![1.0, 128.0 / 255.0, 128.0 / 255.0, 1.0]);
    assert_eq!(spot.params["breakup"], vec![0.5]);
    assert_eq!(spot.params["offset"], vec![1.0, 2.0]);
    assert_eq!(spot.params["wobble"], vec![1.0]);
    assert_eq!(sources.snippet(spot.param_spans["tint"]), "\"#ff8080\"");
    assert_eq!(sources.snippet(spot.param_spans["offset"]), "[1.0, 2.0]");

    let cow = object(&scene, "cow");
    assert!(!cow.casts_shadows);
    assert_eq!(
        cow.model,
        Mat4::from_translation(Vec3::new(2.0, 0.0, 0.0)) * Mat4::from_scale(Vec3::splat(0.5))
    );

    // The unnamed sphere is named after its kind.
    let sphere = object(&scene, "sphere");
    assert_eq!(sphere.mesh.source, "sphere(radius=0.5, segments=64, rings=32)");
    assert_eq!(sources.snippet(sphere.mesh_span), "{ kind = \"sphere\", radius = 0.5 }");
    assert_eq!(scene.triangle_count(), 5856 + 5804 + 2 * 64 * 31);
}

#[test]
fn objects_sharing_a_file_share_one_mesh() {
    let models = models_dir();
    let text = "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n\
                [[object]]\nmesh = \"cow.obj\"\n[[object]]\nmesh = \"cow.obj\"\ntranslate = [1.0, 0.0, 0.0]\n\
                [[object]]\nprimitive = { kind = \"cube\" }\n[[object]]\nprimitive = { kind = \"cube\", size = 1.0 }\n";
    let scene = parse_scene(text, npr_diag::FileId(0), &models).expect("valid scene");
    assert!(Arc::ptr_eq(&scene.objects[0].mesh, &scene.objects[1].mesh));
    assert!(Arc::ptr_eq(&scene.objects[2].mesh, &scene.objects[3].mesh));
    // Derived names are made unique.
    let names: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["cow", "cow-2", "cube", "cube-2"]);
}

#[test]
fn rotation_applies_y_then_x_then_z() {
    let text = "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n\
                [[object]]\nprimitive = { kind = \"cube\" }\nrotate = [90.0, 90.0, 0.0]\n\
                [[object]]\nprimitive = { kind = \"cube\" }\nrotate = [0.0, 90.0, 90.0]\n";
    let scene = parse_scene(text, npr_diag::FileId(0), Path::new(".")).expect("valid scene");
    // Y first: +Z → +X, then X leaves +X alone. (X first would give -Y.)
    let turned = scene.objects[0].model.transform_vector3(Vec3::Z);
    assert!((turned - Vec3::X).length() < 1e-6, "{turned:?}");
    // Y first: +Z → +X, then Z turns +X to +Y.
    let turned = scene.objects[1].model.transform_vector3(Vec3::Z);
    assert!((turned - Vec3::Y).length() < 1e-6, "{turned:?}");
}

// ---- glTF: a generated quad, as .gltf with a data URI and as .glb ----

/// A unit quad in the XY plane facing +Z, with glTF's top-left UVs.
struct QuadAsset {
    with_normals: bool,
    with_uvs: bool,
    with_tangents: bool,
    indices: [u16; 6],
    /// JSON for the `nodes` array; node 0 is the scene root and the mesh is
    /// mesh 0.
    nodes: &'static str,
}

const POSITIONS: [[f32; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
const UVS: [[f32; 2]; 4] = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
const INDICES: [u16; 6] = [0, 1, 2, 0, 2, 3];

impl QuadAsset {
    fn plain(nodes: &'static str) -> Self {
        QuadAsset {
            with_normals: true,
            with_uvs: true,
            with_tangents: false,
            indices: INDICES,
            nodes,
        }
    }

    /// The binary buffer and the glTF JSON (without `buffers`), given the
    /// buffer entry to use.
    fn build(&self, buffer_entry: &dyn Fn(usize) -> String) -> (Vec<u8>, String) {
        let mut bytes = Vec::new();
        let mut views = Vec::new();
        let mut accessors = Vec::new();
        let mut attributes = Vec::new();
        let mut add = |bytes: &mut Vec<u8>, data: Vec<u8>, accessor: String, attribute: Option<&str>| {
            views.push(format!(
                r#"{{"buffer":0,"byteOffset":{},"byteLength":{}}}"#,
                bytes.len(),
                data.len()
            ));
            bytes.extend(data);
            let index = accessors.len();
            accessors.push(accessor.replace("VIEW", &(views.len() - 1).to_string()));
            if let Some(name) = attribute {
                attributes.push(format!(r#""{name}":{index}"#));
            }
            index
        };
        let floats = |values: &[f32]| values.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>();
        add(
            &mut bytes,
            floats(POSITIONS.as_flattened()),
            r#"{"bufferView":VIEW,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}"#.into(),
            Some("POSITION"),
        );
        if self.with_normals {
            add(
                &mut bytes,
                floats(&[0.0, 0.0, 1.0].repeat(4)),
                r#"{"bufferView":VIEW,"componentType":5126,"count":4,"type":"VEC3"}"#.into(),
                Some("NORMAL"),
            );
        }
        if self.with_uvs {
            add(
                &mut bytes,
                floats(UVS.as_flattened()),
                r#"{"bufferView":VIEW,"componentType":5126,"count":4,"type":"VEC2"}"#.into(),
                Some("TEXCOORD_0"),
            );
        }
        if self.with_tangents {
            add(
                &mut bytes,
                floats(&[1.0, 0.0, 0.0, 1.0].repeat(4)),
                r#"{"bufferView":VIEW,"componentType":5126,"count":4,"type":"VEC4"}"#.into(),
                Some("TANGENT"),
            );
        }
        let index_bytes: Vec<u8> = self.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let indices = add(
            &mut bytes,
            index_bytes,
            r#"{"bufferView":VIEW,"componentType":5123,"count":6,"type":"SCALAR"}"#.into(),
            None,
        );
        while bytes.len() % 4 != 0 {
            bytes.push(0);
        }
        let json = format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":{},"meshes":[{{"primitives":[{{"attributes":{{{}}},"indices":{indices}}}]}}],"accessors":[{}],"bufferViews":[{}],"buffers":[{}]}}"#,
            self.nodes,
            attributes.join(","),
            accessors.join(","),
            views.join(","),
            buffer_entry(bytes.len()),
        );
        (bytes, json)
    }

    fn gltf_with_data_uri(&self) -> Vec<u8> {
        let (bytes, _) = self.build(&|_| String::new());
        let encoded = base64(&bytes);
        let (_, json) = self.build(&|length| {
            format!(r#"{{"byteLength":{length},"uri":"data:application/octet-stream;base64,{encoded}"}}"#)
        });
        json.into_bytes()
    }

    fn glb(&self) -> Vec<u8> {
        let (mut bin, json) = self.build(&|length| format!(r#"{{"byteLength":{length}}}"#));
        let mut json = json.into_bytes();
        while json.len() % 4 != 0 {
            json.push(b' ');
        }
        while bin.len() % 4 != 0 {
            bin.push(0);
        }
        let total = 12 + 8 + json.len() + 8 + bin.len();
        let mut glb = Vec::with_capacity(total);
        glb.extend(b"glTF");
        glb.extend(2u32.to_le_bytes());
        glb.extend((total as u32).to_le_bytes());
        glb.extend((json.len() as u32).to_le_bytes());
        glb.extend(b"JSON");
        glb.extend(json);
        glb.extend((bin.len() as u32).to_le_bytes());
        glb.extend(b"BIN\0");
        glb.extend(bin);
        glb
    }
}

fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * k)) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// A fresh directory for one test's generated files.
fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("npr-scene-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Loads `file` (written into `dir`) as the only object of a scene.
fn load_single_mesh(dir: &Path, file: &str, bytes: &[u8]) -> Arc<Mesh> {
    std::fs::write(dir.join(file), bytes).expect("write asset");
    let text =
        format!("[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n[[object]]\nmesh = \"{file}\"\n");
    match parse_scene(&text, npr_diag::FileId(0), dir) {
        Ok(scene) => Arc::clone(&scene.objects[0].mesh),
        Err(diagnostics) => panic!("{diagnostics:#?}"),
    }
}

const NESTED_NODES: &str = r#"[{"translation":[1,2,3],"children":[1]},{"scale":[2,2,2],"mesh":0}]"#;

#[test]
fn gltf_round_trip_bakes_node_transforms() {
    let dir = scratch_dir("gltf-round-trip");
    let mesh = load_single_mesh(&dir, "quad.gltf", &QuadAsset::plain(NESTED_NODES).gltf_with_data_uri());
    let expected: Vec<[f32; 3]> = POSITIONS
        .iter()
        .map(|p| [2.0 * p[0] + 1.0, 2.0 * p[1] + 2.0, 3.0])
        .collect();
    assert_eq!(mesh.positions, expected);
    assert_eq!(mesh.normals, vec![[0.0, 0.0, 1.0]; 4]);
    assert_eq!(
        mesh.uvs.as_deref(),
        Some(&UVS[..]),
        "glTF UVs are already top-left: kept as is"
    );
    assert_eq!(mesh.indices, INDICES.map(u32::from));
    // Derived tangents match what a glTF exporter writes for this layout.
    assert_eq!(mesh.tangents.as_deref(), Some(&[[1.0, 0.0, 0.0, 1.0]; 4][..]));
    assert!(mesh.source.ends_with("quad.gltf"));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn glb_round_trip_matches_gltf() {
    let dir = scratch_dir("glb-round-trip");
    let asset = QuadAsset::plain(NESTED_NODES);
    let from_gltf = load_single_mesh(&dir, "quad.gltf", &asset.gltf_with_data_uri());
    let from_glb = load_single_mesh(&dir, "quad.glb", &asset.glb());
    assert_eq!(from_gltf.positions, from_glb.positions);
    assert_eq!(from_gltf.normals, from_glb.normals);
    assert_eq!(from_gltf.uvs, from_glb.uvs);
    assert_eq!(from_gltf.indices, from_glb.indices);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_mirroring_node_flips_winding_and_tangent_handedness() {
    let dir = scratch_dir("gltf-mirror");
    let asset = QuadAsset {
        with_tangents: true,
        ..QuadAsset::plain(r#"[{"scale":[-1,1,1],"mesh":0}]"#)
    };
    let mesh = load_single_mesh(&dir, "mirrored.glb", &asset.glb());
    assert_eq!(mesh.positions[1], [-1.0, 0.0, 0.0]);
    // Normals transform by the inverse transpose: +Z stays +Z.
    assert_eq!(mesh.normals[0], [0.0, 0.0, 1.0]);
    // Triangles still wind counter-clockwise around their normal.
    for triangle in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| Vec3::from_array(mesh.positions[triangle[k] as usize]));
        assert!((b - a).cross(c - a).z > 0.0, "{triangle:?} winds clockwise");
    }
    let tangents = mesh.tangents.as_ref().expect("TANGENT given");
    assert!(tangents.iter().all(|t| *t == [-1.0, 0.0, 0.0, -1.0]), "{tangents:?}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn gltf_without_normals_or_uvs_gets_computed_normals_only() {
    let dir = scratch_dir("gltf-bare");
    let asset = QuadAsset {
        with_normals: false,
        with_uvs: false,
        ..QuadAsset::plain(r#"[{"mesh":0}]"#)
    };
    let mesh = load_single_mesh(&dir, "bare.gltf", &asset.gltf_with_data_uri());
    assert_eq!(mesh.normals, vec![[0.0, 0.0, 1.0]; 4]);
    assert!(mesh.uvs.is_none() && mesh.tangents.is_none());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn base64_encoder_matches_rfc_4648_vectors() {
    assert_eq!(base64(b""), "");
    assert_eq!(base64(b"f"), "Zg==");
    assert_eq!(base64(b"fo"), "Zm8=");
    assert_eq!(base64(b"foo"), "Zm9v");
    assert_eq!(base64(b"foobar"), "Zm9vYmFy");
}

/// Loads `file` expecting one E0402 on its `mesh` string.
fn mesh_error(dir: &Path, file: &str, bytes: &[u8]) -> npr_diag::Diagnostic {
    std::fs::write(dir.join(file), bytes).expect("write asset");
    let text =
        format!("[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n[[object]]\nmesh = \"{file}\"\n");
    let diagnostics = parse_scene(&text, npr_diag::FileId(0), dir).expect_err("a broken asset");
    assert_eq!(diagnostics.len(), 1, "{diagnostics:#?}");
    let diagnostic = diagnostics.into_iter().next().expect("one");
    assert_eq!(diagnostic.code, npr_diag::codes::UNREADABLE_MESH, "{diagnostic:#?}");
    let span = diagnostic.primary_span().expect("span");
    assert_eq!(&text[span.range()], format!("\"{file}\""));
    diagnostic
}

#[test]
fn malformed_gltf_is_an_error_not_a_panic() {
    let dir = scratch_dir("gltf-malformed");
    let out_of_range = QuadAsset {
        indices: [0, 1, 2, 0, 2, 9],
        ..QuadAsset::plain(r#"[{"mesh":0}]"#)
    };
    let d = mesh_error(&dir, "bad-index.glb", &out_of_range.glb());
    assert!(d.message.contains("out of range"), "{d:#?}");
    // A node that is its own child: rejected, without unbounded recursion.
    let cyclic = QuadAsset::plain(r#"[{"mesh":0,"children":[0]}]"#);
    mesh_error(&dir, "cycle.gltf", &cyclic.gltf_with_data_uri());
    // A truncated GLB.
    let glb = QuadAsset::plain(r#"[{"mesh":0}]"#).glb();
    mesh_error(&dir, "truncated.glb", &glb[..glb.len() / 2]);
    // Valid JSON, not glTF.
    mesh_error(&dir, "not-gltf.gltf", b"{\"hello\": 1}");
    let _ = std::fs::remove_dir_all(dir);
}

/// The largest angle (degrees) between a triangle corner's vertex normal and
/// the triangle's face normal, over the mesh.
fn worst_corner_deviation(mesh: &Mesh) -> f32 {
    let mut worst = 0.0f32;
    for t in mesh.indices.chunks_exact(3) {
        let p = [t[0], t[1], t[2]].map(|i| Vec3::from_array(mesh.positions[i as usize]));
        let Some(face) = (p[1] - p[0]).cross(p[2] - p[0]).try_normalize() else {
            continue;
        };
        for &i in t {
            let n = Vec3::from_array(mesh.normals[i as usize]);
            worst = worst.max(n.dot(face).clamp(-1.0, 1.0).acos().to_degrees());
        }
    }
    worst
}

#[test]
fn fandisk_creases_get_split_normals() {
    // examples/scenes/fandisk.toml: `crease_angle = 30` on a mesh without normals.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/scenes/fandisk.toml");
    let text = std::fs::read_to_string(&path).expect("fandisk scene");
    let mut sources = npr_diag::SourceMap::new();
    let creased = load_scene(&path, &mut sources)
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    let smooth_text = text.replace("crease_angle = 30.0", "");
    assert_ne!(smooth_text, text);
    let file = sources.add("fandisk_smooth.toml", smooth_text.clone());
    let smooth = parse_scene(&smooth_text, file, path.parent().expect("dir"))
        .unwrap_or_else(|d| panic!("{}", npr_diag::diagnostic::render(&d, &sources, false)));
    let (c, s) = (&creased.objects[0].mesh, &smooth.objects[0].mesh);
    assert_sound_attributes(c);
    // Same triangles; vertices on creases duplicated.
    assert_eq!(c.triangle_count(), s.triangle_count());
    assert_eq!(s.vertex_count(), 6475);
    assert!(
        c.vertex_count() > s.vertex_count() + 500,
        "{} vertices",
        c.vertex_count()
    );
    // Every corner normal averages only faces within 30° of its own, so it
    // stays within 30° of its face; smooth normals bend across the creases.
    let (dc, ds) = (worst_corner_deviation(c), worst_corner_deviation(s));
    println!(
        "fandisk: {} vertices creased ({dc:.1}° worst corner), {} smooth ({ds:.1}°)",
        c.vertex_count(),
        s.vertex_count()
    );
    assert!(dc <= 30.0 + 1e-3, "creased: {dc}°");
    assert!(ds > 40.0, "smooth: {ds}°");
}

#[test]
fn crease_angle_is_checked() {
    for (value, message) in [
        ("0.0", "must be in (0, 180]"),
        ("200.0", "must be in (0, 180]"),
        ("\"sharp\"", "crease_angle"),
    ] {
        let text = format!("[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\nprimitive = {{ kind = \"cube\" }}\ncrease_angle = {value}\n");
        let mut sources = npr_diag::SourceMap::new();
        let file = sources.add("crease.toml", text.clone());
        let Err(diagnostics) = parse_scene(&text, file, Path::new(".")) else {
            panic!("crease_angle = {value} was accepted");
        };
        let rendered = npr_diag::diagnostic::render(&diagnostics, &sources, false);
        assert!(rendered.contains(message), "{value}: {rendered}");
    }
    // On a cube (90° edges) any angle below 90° gives each face its own
    // normal: 24 vertices, as the primitive already has.
    let text = "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\nprimitive = { kind = \"cube\" }\ncrease_angle = 45.0\n";
    let mut sources = npr_diag::SourceMap::new();
    let file = sources.add("crease.toml", text.to_string());
    let scene = parse_scene(text, file, Path::new(".")).expect("valid");
    assert!(worst_corner_deviation(&scene.objects[0].mesh) < 0.01);
}
