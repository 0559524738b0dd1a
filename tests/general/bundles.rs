//! `npr compile -o STYLE.nprb`: one bundle file that `npr render
//! --compiled` runs as the style itself, with its image files inside it
//! (the originals deleted before the run), and a bundle that is damaged or
//! incomplete refused with E0504 naming what is wrong.

use crate::common::cli::{npr, scratch, stderr};
use std::path::Path;

/// A style that samples an image file of its own folder.
const STYLE: &str = r#"style "Bundled paper"
texture paper = image("paper.png", srgb)
pass shade: render(scene) {
  let lit = lambert(normal, light.dir)
  out color: rgba8unorm = vec4(sample(paper, uv).rgb * (0.3 + 0.7 * lit), 1.0)
}
output shade.color
"#;

/// `dir` with the style, its image (a gradient, so that a wrong or missing
/// texture shows) and a scene of one sphere.
fn style_folder(dir: &Path) {
    std::fs::write(dir.join("paper.npr"), STYLE).expect("style");
    let image = image::RgbaImage::from_fn(16, 16, |x, y| image::Rgba([(x * 16) as u8, (y * 16) as u8, 128, 255]));
    image.save(dir.join("paper.png")).expect("image");
    std::fs::write(
        dir.join("scene.toml"),
        "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 40.0\n\n[[object]]\nprimitive = { kind = \"sphere\", radius = 1.0 }\n",
    )
    .expect("scene");
}

fn path(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

fn ok(o: &std::process::Output) {
    assert!(o.status.success(), "npr failed:\n{}", stderr(o));
}

#[test]
fn a_bundle_renders_as_its_style_with_its_images_inside() {
    let dir = scratch("bundles", "renders");
    style_folder(&dir);
    let (style, scene, bundle) = (dir.join("paper.npr"), dir.join("scene.toml"), dir.join("paper.nprb"));
    let direct = dir.join("direct.png");
    ok(&npr(&[
        "render",
        path(&style),
        "--scene",
        path(&scene),
        "--size",
        "64x64",
        "-o",
        path(&direct),
    ]));
    ok(&npr(&[
        "compile",
        path(&style),
        "--scene",
        path(&scene),
        "-o",
        path(&bundle),
    ]));
    // The bundle needs neither the style nor its image any more.
    std::fs::remove_file(dir.join("paper.png")).expect("remove image");
    std::fs::remove_file(&style).expect("remove style");
    let from_bundle = dir.join("bundle.png");
    ok(&npr(&[
        "render",
        "--compiled",
        path(&bundle),
        "--scene",
        path(&scene),
        "--size",
        "64x64",
        "-o",
        path(&from_bundle),
    ]));
    let a = image::open(&direct).expect("direct").to_rgba8();
    let b = image::open(&from_bundle).expect("bundle").to_rgba8();
    assert_eq!(a.dimensions(), b.dimensions());
    assert!(
        a == b,
        "the bundle's image differs from the style's ({} and {})",
        direct.display(),
        from_bundle.display()
    );
    // Not trivially equal: the texture's gradient is in the picture.
    let centre = a.get_pixel(32, 32).0;
    let edge = a.get_pixel(32, 20).0;
    assert_ne!(centre, edge, "the sphere shows no texture");
}

/// The entries of a bundle, as `npr_abi::bundle` documents the layout.
fn entries(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let u32_at = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().expect("4 bytes")) as usize;
    let count = u32_at(12);
    let mut at = 16;
    let mut out = Vec::new();
    for _ in 0..count {
        let n = u32_at(at);
        let name = String::from_utf8(bytes[at + 4..at + 4 + n].to_vec()).expect("name");
        at += 4 + n;
        let len = u64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes")) as usize;
        out.push((name, bytes[at + 8..at + 8 + len].to_vec()));
        at += 8 + len;
    }
    assert_eq!(at, bytes.len(), "entries end at the end of the file");
    out
}

fn write_bundle(path: &Path, entries: &[(String, Vec<u8>)]) {
    let mut out = b"NPRBNDL\0".to_vec();
    out.extend_from_slice(&npr_abi::bundle::BUNDLE_VERSION.to_le_bytes());
    out.extend_from_slice(&(entries.len() as u32).to_le_bytes());
    for (name, data) in entries {
        out.extend_from_slice(&(name.len() as u32).to_le_bytes());
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(&(data.len() as u64).to_le_bytes());
        out.extend_from_slice(data);
    }
    std::fs::write(path, out).expect("write bundle");
}

#[test]
fn a_damaged_or_incomplete_bundle_is_e0504_naming_what_is_wrong() {
    let dir = scratch("bundles", "damaged");
    style_folder(&dir);
    let (style, scene, bundle) = (dir.join("paper.npr"), dir.join("scene.toml"), dir.join("paper.nprb"));
    ok(&npr(&["compile", path(&style), "-o", path(&bundle)]));
    let bytes = std::fs::read(&bundle).expect("bundle");
    let good = entries(&bytes);
    assert!(good.iter().any(|(n, _)| n == "manifest.json"));
    assert!(
        good.iter()
            .any(|(n, _)| n.starts_with("file:") && n.ends_with("paper.png")),
        "no image entry"
    );

    let render = |file: &Path| {
        npr(&[
            "render",
            "--compiled",
            path(file),
            "--scene",
            path(&scene),
            "-o",
            path(&dir.join("x.png")),
        ])
    };
    let refused = |file: &Path, wanted: &str| {
        let o = render(file);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        let text = stderr(&o);
        assert!(
            text.contains("error[E0504]") && text.contains(wanted),
            "no E0504 with `{wanted}` in:\n{text}"
        );
        assert!(!dir.join("x.png").exists(), "an image was written");
    };
    let cut = dir.join("cut.nprb");
    std::fs::write(&cut, &bytes[..bytes.len() - 10]).expect("write");
    refused(&cut, "truncated");
    let no_image = dir.join("no_image.nprb");
    write_bundle(
        &no_image,
        &good
            .iter()
            .filter(|(n, _)| !n.starts_with("file:"))
            .cloned()
            .collect::<Vec<_>>(),
    );
    refused(&no_image, "paper.png");
    let twice = dir.join("twice.nprb");
    write_bundle(&twice, &[good.clone(), vec![good[0].clone()]].concat());
    refused(&twice, "twice");
    let mut newer = bytes.clone();
    newer[8..12].copy_from_slice(&(npr_abi::bundle::BUNDLE_VERSION + 1).to_le_bytes());
    let newer_path = dir.join("newer.nprb");
    std::fs::write(&newer_path, newer).expect("write");
    refused(&newer_path, "compile the style again");
    refused(&dir.join("paper.png"), "not an npr bundle");
}
