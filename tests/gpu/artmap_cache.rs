//! The art-map cache through `npr render` and the runner (Klein et al. 2000
//! §4.2 builds; docs in `runner/src/artmap_cache.rs`): reused, missed when
//! the source or the filter changes, a damaged entry rebuilt, and a second
//! renderer in one process served from memory.

use crate::common;

use common::artmaps::{compile, grey_png, scratch};
use common::{gpu, root};
use npr_runner::Renderer;
use std::path::Path;

/// `npr render` with its own cache directory; its stderr.
fn render_cli(style: &Path, scene: &Path, out: &Path, cache: &Path) -> String {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_npr"))
        .arg("render")
        .arg(style)
        .arg("--scene")
        .arg(scene)
        .arg("-o")
        .arg(out)
        .args(["--size", "32x32"])
        .env("NPR_CACHE_DIR", cache)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "npr render failed:\n{stderr}");
    stderr
}

#[test]
fn the_cache_is_reused_and_missed_when_the_source_or_the_filter_changes() {
    let dir = scratch("cache");
    let cache = dir.join("cache");
    grey_png(&dir.join("src.png"), 64, 120);
    let hatching = std::fs::read_to_string(root().join("examples/filters/hatching.npr")).unwrap();
    std::fs::write(dir.join("filter.npr"), &hatching).unwrap();
    let style = dir.join("style.npr");
    std::fs::write(
        &style,
        "style \"cached\"\n\
         texture t = artmap(image(\"src.png\", srgb), filter: \"filter.npr\") { wrap: repeat }\n\
         pass shade: render(scene) {\n  out color: rgba8unorm = vec4(sample_biased(t, uv * 4.0).rgb, 1.0)\n}\n\
         output shade.color\n",
    )
    .unwrap();
    let scene = root().join("examples/scenes/spot.toml");
    let png = |n: &str| dir.join(format!("{n}.png"));

    let first = render_cli(&style, &scene, &png("first"), &cache);
    assert!(first.contains("art-map `t`: 7 level(s) filtered and cached"), "{first}");
    let entries = || std::fs::read_dir(cache.join("artmaps")).unwrap().count();
    assert_eq!(entries(), 1);
    let second = render_cli(&style, &scene, &png("second"), &cache);
    assert!(second.contains("read from the cache"), "{second}");
    assert_eq!(
        std::fs::read(png("first")).unwrap(),
        std::fs::read(png("second")).unwrap()
    );

    // A filter whose parameter default changed is another art-map.
    std::fs::write(dir.join("filter.npr"), hatching.replace("= 4 in 2..32", "= 6 in 2..32")).unwrap();
    let changed_filter = render_cli(&style, &scene, &png("filter"), &cache);
    assert!(changed_filter.contains("filtered and cached"), "{changed_filter}");
    assert_eq!(entries(), 2);
    assert_ne!(
        std::fs::read(png("first")).unwrap(),
        std::fs::read(png("filter")).unwrap()
    );

    // So is a source image with other bytes.
    grey_png(&dir.join("src.png"), 64, 121);
    let changed_source = render_cli(&style, &scene, &png("source"), &cache);
    assert!(changed_source.contains("filtered and cached"), "{changed_source}");
    assert_eq!(entries(), 3);

    // A damaged entry is rebuilt (and replaced), never read.
    for e in std::fs::read_dir(cache.join("artmaps")).unwrap() {
        let path = e.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        std::fs::write(&path, &bytes[..bytes.len() / 2]).unwrap();
    }
    let damaged = render_cli(&style, &scene, &png("damaged"), &cache);
    assert!(damaged.contains("filtered and cached"), "{damaged}");
    assert_eq!(
        std::fs::read(png("source")).unwrap(),
        std::fs::read(png("damaged")).unwrap()
    );
    let again = render_cli(&style, &scene, &png("again"), &cache);
    assert!(again.contains("read from the cache"), "{again}");
}

#[test]
fn a_second_renderer_in_the_same_process_reuses_the_art_map_from_memory() {
    let dir = scratch("memory");
    grey_png(&dir.join("src.png"), 32, 77);
    let text = format!(
        "style \"memory\"\n\
         texture t = artmap(image(\"src.png\", srgb), filter: \"{}\") {{ wrap: repeat }}\n\
         pass read: image() {{\n  out v: rgba16float = sample_biased(t, screen_uv)\n}}\n\
         output read.v\n",
        root().join("examples/filters/hatching.npr").display()
    );
    let program = compile(&text, &dir);
    let g = gpu();
    let scene = npr_runner::scene::Scene::empty();
    let first = Renderer::new(&g.device, &g.queue, &program, &scene).unwrap();
    let second = Renderer::new(&g.device, &g.queue, &program, &scene).unwrap();
    assert_eq!(first.artmap_builds().len(), 1);
    assert_eq!(
        second.artmap_builds()[0].origin,
        npr_runner::artmap_cache::Origin::Memory
    );
    assert_eq!(second.artmap_builds()[0].levels, 6);
}
