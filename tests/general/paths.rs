//! The paths policy (docs/PATHS.md) through the `npr` binary: paths are
//! relative to the file naming them and must stay inside the root (by
//! default the deepest directory holding the style and the scene, or
//! `--root DIR`); absolute paths, `..` out of the root and symbolic links
//! out of it are E0406 naming the root, unless `--allow-path DIR` admits
//! them. The examples work from any working directory.
//!
//! Layout of each case's scratch directory:
//! `proj/` (style, scene, `textures/`, `link.png` → `../outside/tex.png`)
//! and `outside/` (`tex.png`, `shared.npr`, `tri.obj`).

use crate::common;

use common::root;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn layout(name: &str) -> PathBuf {
    let base = Path::new(env!("CARGO_TARGET_TMPDIR")).join("paths").join(name);
    let _ = std::fs::remove_dir_all(&base);
    for d in ["proj/textures", "outside"] {
        std::fs::create_dir_all(base.join(d)).expect("dirs");
    }
    let png = image::RgbaImage::from_pixel(2, 2, image::Rgba([200, 100, 50, 255]));
    png.save(base.join("outside/tex.png")).expect("png");
    png.save(base.join("proj/textures/ok.png")).expect("png");
    std::fs::write(
        base.join("outside/tri.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
    )
    .expect("obj");
    std::fs::write(
        base.join("outside/shared.npr"),
        "style \"Shared\"\nparam gain: float = 0.5 in 0..1\n",
    )
    .expect("npr");
    #[cfg(unix)]
    std::os::unix::fs::symlink("../outside/tex.png", base.join("proj/link.png")).expect("symlink");
    base.canonicalize().expect("canonical")
}

fn style_with_texture(path: &str) -> String {
    format!(
        "style \"P\"\ntexture t = image(\"{path}\", srgb)\npass p: render(scene) {{\n  out c: rgba8unorm = t\n}}\noutput p.c\n"
    )
}

fn scene_with_mesh(mesh: &str) -> String {
    format!("[camera]\nposition = [0.0, 0.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\nmesh = \"{mesh}\"\n")
}

/// `npr check proj/style.npr --scene proj/scene.toml extra…`, run from `cwd`.
fn check(base: &Path, style: &str, scene: &str, extra: &[&str], cwd: &Path) -> Output {
    std::fs::write(base.join("proj/style.npr"), style).expect("style");
    std::fs::write(base.join("proj/scene.toml"), scene).expect("scene");
    Command::new(env!("CARGO_BIN_EXE_npr"))
        .arg("check")
        .arg(base.join("proj/style.npr"))
        .arg("--scene")
        .arg(base.join("proj/scene.toml"))
        .args(extra)
        .current_dir(cwd)
        .output()
        .expect("npr runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit 1 with E0406 at `written`, naming the root.
fn assert_refused(o: &Output, written: &str, root_dir: &Path) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("error[E0406]"), "{e}");
    assert!(e.contains(&root_dir.display().to_string()), "the root is named: {e}");
    assert!(
        e.contains(&format!("\"{written}\"")),
        "the label shows the path as written: {e}"
    );
}

const SPHERE: &str =
    "[camera]\nposition = [0.0, 0.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\n\n[[object]]\nprimitive = { kind = \"sphere\" }\n";

#[test]
fn a_texture_inside_the_root_is_read() {
    let base = layout("inside");
    let o = check(&base, &style_with_texture("textures/ok.png"), SPHERE, &[], &base);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_texture_leaving_the_root_is_refused_naming_the_root() {
    let base = layout("escape");
    let o = check(&base, &style_with_texture("../outside/tex.png"), SPHERE, &[], &base);
    assert_refused(&o, "../outside/tex.png", &base.join("proj"));
    assert!(stderr(&o).contains("leaves the root"), "{}", stderr(&o));
}

#[test]
fn an_absolute_texture_path_is_refused_unless_its_directory_is_allowed() {
    let base = layout("absolute");
    let abs = base.join("proj/textures/ok.png").display().to_string();
    // Absolute even inside the root: it would not work on another machine.
    let o = check(&base, &style_with_texture(&abs), SPHERE, &[], &base);
    assert_refused(&o, &abs, &base.join("proj"));
    assert!(stderr(&o).contains("is an absolute path"), "{}", stderr(&o));
    let allow = base.join("proj/textures");
    let o = check(
        &base,
        &style_with_texture(&abs),
        SPHERE,
        &["--allow-path", allow.to_str().expect("utf-8")],
        &base,
    );
    assert!(o.status.success(), "{}", stderr(&o));
}

#[cfg(unix)]
#[test]
fn a_symbolic_link_out_of_the_root_is_refused() {
    let base = layout("symlink");
    let o = check(&base, &style_with_texture("link.png"), SPHERE, &[], &base);
    assert_refused(&o, "link.png", &base.join("proj"));
    assert!(stderr(&o).contains("through a symbolic link"), "{}", stderr(&o));
}

#[test]
fn a_use_leaving_the_root_is_refused_before_it_is_read_and_root_widens_it() {
    let base = layout("use");
    let style =
        "style \"U\"\nuse \"../outside/shared.npr\"\npass p: image() {\n  out c: r8unorm = gain\n}\noutput p.c\n";
    let o = check(&base, style, SPHERE, &[], &base);
    assert_refused(&o, "../outside/shared.npr", &base.join("proj"));
    let o = check(&base, style, SPHERE, &["--root", base.to_str().expect("utf-8")], &base);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_scene_mesh_leaving_the_root_is_refused_at_its_toml_value() {
    let base = layout("mesh");
    let style = "style \"M\"\npass p: render(scene) {\n  out c: rgba8unorm = vec4(1.0)\n}\noutput p.c\n";
    let o = check(&base, style, &scene_with_mesh("../outside/tri.obj"), &[], &base);
    assert_refused(&o, "../outside/tri.obj", &base.join("proj"));
    assert!(
        stderr(&o).contains("scene.toml:6:8"),
        "at the TOML value: {}",
        stderr(&o)
    );
    let outside = base.join("outside");
    let o = check(
        &base,
        style,
        &scene_with_mesh("../outside/tri.obj"),
        &["--allow-path", outside.to_str().expect("utf-8")],
        &base,
    );
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_root_that_is_not_a_directory_is_a_bad_argument() {
    let base = layout("bad-root");
    let o = check(
        &base,
        &style_with_texture("textures/ok.png"),
        SPHERE,
        &["--root", "no/such/dir"],
        &base,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("error[E0502]: --root no/such/dir: not a directory"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn the_examples_render_from_any_working_directory() {
    // A scene in examples/scenes naming ../models and ../textures, a style
    // with textures and another that `use`s lib/: the root is examples/.
    let elsewhere = std::env::temp_dir();
    for (style, scene) in [
        ("examples/age_of_sail.npr", "examples/scenes/age_of_sail.toml"),
        ("examples/halftone.npr", "examples/scenes/cows.toml"),
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_npr"))
            .arg("render")
            .arg(root().join(style))
            .arg("--scene")
            .arg(root().join(scene))
            .args(["--size", "32x32", "-o", "/dev/null"])
            .current_dir(&elsewhere)
            .output()
            .expect("npr runs");
        assert!(o.status.success(), "{style}: {}", stderr(&o));
    }
}
