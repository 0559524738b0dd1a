//! The `.npr` asset loader's diagnostics, as Bevy's log gets them: npr's
//! rendering with the code and `file:line:col`; a style that is not
//! UTF-8 is E0007 at its first bad byte.

use bevy_mod_npr::NprStyleLoader;
use std::path::Path;

fn loader() -> NprStyleLoader {
    NprStyleLoader {
        root: Path::new(env!("CARGO_TARGET_TMPDIR")).join("bevy_mod_npr_loader"),
    }
}

#[test]
fn a_style_that_does_not_compile_is_its_code_at_its_place() {
    let text =
        "style \"Broken\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(1.0, 0.0, 0.0, 1.0) +\n}\noutput p.c\n";
    let e = loader()
        .compile(Path::new("styles/broken.npr"), text.as_bytes().to_vec())
        .expect_err("a syntax error");
    assert_eq!(e.codes, vec!["E0001"], "{}", e.rendered);
    assert!(e.rendered.contains("error[E0001]"), "{}", e.rendered);
    // The file as it is on disk, under the asset root, at the line and column of the error.
    let place = format!("{}:3:49", loader().root.join("styles/broken.npr").display());
    assert!(e.rendered.contains(&place), "no `{place}` in:\n{}", e.rendered);
    assert!(e.to_string().contains("E0001"), "{e}");
}

#[test]
fn a_style_that_is_not_utf8_is_e0007() {
    let mut bytes = b"style \"Latin\"\n// caf".to_vec();
    bytes.push(0xe9);
    let e = loader().compile(Path::new("latin.npr"), bytes).expect_err("not UTF-8");
    assert_eq!(e.codes, vec!["E0007"], "{}", e.rendered);
    assert!(e.rendered.contains("latin.npr:2:"), "{}", e.rendered);
}

#[test]
fn a_style_that_compiles_is_an_asset_with_its_name_and_kept_params() {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/toon.npr"))
        .expect("examples/toon.npr");
    let asset = loader()
        .compile(Path::new("toon.npr"), text.into_bytes())
        .unwrap_or_else(|e| panic!("{}", e.rendered));
    assert_eq!(asset.name(), "Toon");
    // Every param stays a uniform, so NprParams can change it.
    let bands = asset
        .program()
        .manifest
        .params
        .iter()
        .find(|p| p.name == "bands")
        .expect("bands");
    assert_eq!(bands.binding, npr_abi::manifest::ParamBinding::Uniform);
}
