//! npr's own lines over Blender's frame, depth-tested against Blender's
//! depth (issue 47 part 1, `depth: test(input)`): `examples/post/lines_over.npr`
//! draws the borders and silhouettes of the mirrored scene
//! (`tests/data/blender/render_passes.py`) over Blender's colour.
//!
//! The ground's far border runs behind both spheres in Blender's frame. The
//! silhouettes are turned off (`outline_width = 0px`) and the border drawn
//! pure red, so that every red pixel is the border's. The truth is measured
//! in f64: each border pixel's depth is where its pixel's ray meets the
//! ground (y = 0), and Blender's depth is read from its EXR. Where every
//! pixel within 2 px has Blender's depth nearer (by over 10 %: a sphere is
//! 3 m nearer than the border, the ground next to the border at most 0.3 m),
//! the border is hidden; where the pixel itself is not nearer, it shows
//! within 1 px. With the host's depth cleared to far, all of the border
//! shows, and the embedding API (`set_input`) gives the same bytes as
//! `--input` files of the same values.

use crate::blender_scene::{blender, channel, npr, root, scratch};
use npr_runner::inputs::files::{read_exr, ExrChannels};
use npr_runner::inputs::{ColorEncoding, DepthConvention, SourceConvention};
use std::path::Path;

const STYLE: &str = "examples/post/lines_over.npr";
/// The camera of `render_passes.py`, in npr's axes.
const EYE: [f64; 3] = [0.0, 1.6, 5.0];
const TARGET: [f64; 3] = [0.0, 0.5, 0.0];
const FOV_Y_DEG: f64 = 40.0;
/// The ground's half size: its far border is z = −3, y = 0, |x| ≤ 3.
const HALF: f64 = 3.0;
const SETS: [&str; 4] = ["--set", "outline_width=0px", "--set", "rim_ink=#ff0000"];

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn unit(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// The camera's frame in f64: right, up, forward (a look-at with +y up).
struct Camera {
    right: [f64; 3],
    up: [f64; 3],
    forward: [f64; 3],
    tan_half: f64,
    aspect: f64,
    size: (f64, f64),
}

impl Camera {
    fn new(width: u32, height: u32) -> Camera {
        let forward = unit(sub(TARGET, EYE));
        let right = unit(cross(forward, [0.0, 1.0, 0.0]));
        Camera {
            up: cross(right, forward),
            right,
            forward,
            tan_half: (FOV_Y_DEG.to_radians() / 2.0).tan(),
            aspect: f64::from(width) / f64::from(height),
            size: (f64::from(width), f64::from(height)),
        }
    }

    /// `p`'s position in pixels (x right, y down).
    fn project(&self, p: [f64; 3]) -> (f64, f64) {
        let rel = sub(p, EYE);
        let z = dot(rel, self.forward);
        let ndc = (
            dot(rel, self.right) / (z * self.tan_half * self.aspect),
            dot(rel, self.up) / (z * self.tan_half),
        );
        ((ndc.0 + 1.0) / 2.0 * self.size.0, (1.0 - ndc.1) / 2.0 * self.size.1)
    }

    /// The view depth where the ray through pixel (x, y)'s centre meets the
    /// ground plane y = 0 (infinite above the horizon).
    fn ground_depth(&self, x: usize, y: usize) -> f64 {
        let ndc = (
            (x as f64 + 0.5) / self.size.0 * 2.0 - 1.0,
            1.0 - (y as f64 + 0.5) / self.size.1 * 2.0,
        );
        let (sx, sy) = (ndc.0 * self.tan_half * self.aspect, ndc.1 * self.tan_half);
        // Along the ray, one unit of view depth per unit of `t`.
        let dir_y = self.forward[1] + sx * self.right[1] + sy * self.up[1];
        if dir_y >= 0.0 {
            f64::INFINITY
        } else {
            -EYE[1] / dir_y
        }
    }
}

/// Pixels where the red border was drawn: red over Blender's grey scene.
fn red(img: &image::RgbaImage) -> Vec<Vec<bool>> {
    (0..img.height())
        .map(|y| {
            (0..img.width())
                .map(|x| {
                    let [r, g, b, _] = img.get_pixel(x, y).0;
                    i32::from(r) > i32::from(g.max(b)) + 60
                })
                .collect()
        })
        .collect()
}

fn within(m: &[Vec<bool>], x: usize, y: usize, r: usize) -> impl Iterator<Item = bool> + '_ {
    let (h, w) = (m.len(), m[0].len());
    (y.saturating_sub(r)..(y + r + 1).min(h))
        .flat_map(move |yy| (x.saturating_sub(r)..(x + r + 1).min(w)).map(move |xx| m[yy][xx]))
}

/// Blender's colour and depth as single-layer EXRs (the same f32 values
/// the multi-layer file holds), and a depth cleared to Cycles' "nothing
/// hit" (1e10) everywhere.
fn write_inputs(exr: &ExrChannels, dir: &Path) {
    let (w, h) = (exr.width as usize, exr.height as usize);
    let c = ["R", "G", "B", "A"].map(|a| channel(exr, &format!("ViewLayer.Combined.{a}")));
    let z = channel(exr, "ViewLayer.Depth.Z");
    exr::prelude::write_rgba_file(dir.join("colour.exr"), w, h, |x, y| {
        let i = y * w + x;
        (c[0][i], c[1][i], c[2][i], c[3][i])
    })
    .expect("write colour");
    exr::prelude::write_rgba_file(dir.join("depth.exr"), w, h, |x, y| (z[y * w + x], 0.0, 0.0, 1.0))
        .expect("write depth");
    exr::prelude::write_rgba_file(dir.join("far.exr"), w, h, |_, _| (1e10f32, 0.0, 0.0, 1.0)).expect("write far");
}

fn render(dir: &Path, depth: &str, out: &str) -> image::RgbaImage {
    let (_, toml) = blender();
    let file = |n: &str| dir.join(n).display().to_string();
    let mut args = vec![
        "render".to_string(),
        STYLE.to_string(),
        "--scene".to_string(),
        toml.display().to_string(),
        "--input".to_string(),
        format!("color_in={}", file("colour.exr")),
        "--input".to_string(),
        format!("depth_in={}", file(depth)),
        "-o".to_string(),
        file(out),
    ];
    args.extend(SETS.iter().map(|s| s.to_string()));
    npr(&args.iter().map(String::as_str).collect::<Vec<_>>());
    image::open(dir.join(out)).expect("read output").to_rgba8()
}

#[test]
fn lines_over_blender_are_hidden_exactly_where_blenders_depth_is_nearer() {
    let (exr_path, _) = blender();
    let exr = read_exr("passes", exr_path).expect("read Blender's EXR");
    let dir = scratch("lines_over");
    std::fs::create_dir_all(&dir).expect("scratch");
    write_inputs(&exr, &dir);
    let tested = render(&dir, "depth.exr", "tested.png");
    let far = render(&dir, "far.exr", "far.png");
    let (w, h) = (exr.width as usize, exr.height as usize);
    assert_eq!((tested.width() as usize, tested.height() as usize), (w, h));
    let (shown, all) = (red(&tested), red(&far));
    let camera = Camera::new(exr.width, exr.height);

    // With the host's depth far, the whole far border shows: every point
    // of it inside the image has red within 1 px.
    let mut samples = 0;
    for i in 0..=600 {
        let x = -HALF + 2.0 * HALF * f64::from(i) / 600.0;
        let (u, v) = camera.project([x, 0.0, -HALF]);
        if u < 2.0 || v < 2.0 || u > w as f64 - 2.0 || v > h as f64 - 2.0 {
            continue;
        }
        samples += 1;
        assert!(
            within(&all, u as usize, v as usize, 1).any(|r| r),
            "the border at x = {x:.3} m ({u:.1}, {v:.1}) px is missing with the host's depth far ({})",
            dir.join("far.png").display()
        );
    }
    assert!(samples > 300, "the far border crosses the image: {samples} samples");

    // Blender's depth nearer than the border's, per pixel, in f64.
    let z = channel(&exr, "ViewLayer.Depth.Z");
    let nearer: Vec<Vec<bool>> = (0..h)
        .map(|y| {
            (0..w)
                .map(|x| f64::from(z[y * w + x]) < 0.9 * camera.ground_depth(x, y))
                .collect()
        })
        .collect();
    let (mut hidden, mut visible) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            assert!(
                !shown[y][x] || all[y][x],
                "({x}, {y}) is red with Blender's depth but not without it"
            );
            if !all[y][x] {
                continue;
            }
            if within(&nearer, x, y, 2).all(|n| n) {
                hidden += 1;
                assert!(
                    !shown[y][x],
                    "the border at ({x}, {y}) shows though Blender's depth is nearer all around ({}: Blender {:.3} m, border {:.3} m)",
                    dir.join("tested.png").display(),
                    z[y * w + x],
                    camera.ground_depth(x, y)
                );
            } else if !nearer[y][x] {
                visible += 1;
                assert!(
                    within(&shown, x, y, 1).any(|r| r),
                    "the border at ({x}, {y}) is hidden though Blender's depth there is not nearer ({}: Blender {:.3} m, border {:.3} m)",
                    dir.join("tested.png").display(),
                    z[y * w + x],
                    camera.ground_depth(x, y)
                );
            }
        }
    }
    // Both spheres hide a stretch of the border (54 red pixels of the far
    // border with Blender's depth far, measured); the rest of it, and the
    // side borders, show (111).
    eprintln!("border pixels: {hidden} behind a sphere, {visible} in front of everything");
    assert!(hidden > 40, "only {hidden} border pixels are behind a sphere");
    assert!(visible > 80, "only {visible} border pixels are in front of everything");

    // The embedding API, given the same values as textures, draws the same bytes.
    let api = through_api(&exr);
    let differing = api
        .chunks(4)
        .zip(tested.as_raw().chunks(4))
        .filter(|(a, f)| a != f)
        .count();
    if differing > 0 {
        image::RgbaImage::from_raw(exr.width, exr.height, api.clone())
            .expect("api image")
            .save(dir.join("api.png"))
            .expect("save api.png");
    }
    assert_eq!(
        differing,
        0,
        "the API and --input differ in {differing} pixels (see {})",
        dir.join("api.png").display()
    );
}

/// A texture of `format` holding `texels` (row by row), for `set_input`.
fn texture(format: wgpu::TextureFormat, size: (u32, u32), bytes: &[u8], texel_bytes: u32) -> wgpu::Texture {
    let g = crate::common::gpu();
    let extent = wgpu::Extent3d {
        width: size.0,
        height: size.1,
        depth_or_array_layers: 1,
    };
    let t = g.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("host"),
        size: extent,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    g.queue.write_texture(
        t.as_image_copy(),
        bytes,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(size.0 * texel_bytes),
            rows_per_image: Some(size.1),
        },
        extent,
    );
    t
}

/// The style through `StyleRuntime`: Blender's colour and depth as the
/// host's textures, the mirrored scene's objects as its instances.
fn through_api(exr: &ExrChannels) -> Vec<u8> {
    use npr_runner::embed::{Frame, Lights, StyleRuntime, Target};
    let g = crate::common::gpu();
    let size = (exr.width, exr.height);
    let (_, toml) = blender();
    let scene = npr_runner::scene::load_scene(toml, &mut npr_diag::SourceMap::new()).expect("scene");
    let mut sources = npr_diag::SourceMap::new();
    // Kept as uniforms, so that the host sets them as `--set` folds them.
    let options = npr_compiler::CompileOptions {
        keep_params: true,
        ..Default::default()
    };
    let compiled = npr_compiler::compile_file(&root().join(STYLE), &mut sources, &options).expect("compile");
    let mut runtime = StyleRuntime::new(&g.device, &g.queue, compiled.program()).expect("runtime");
    for pair in SETS.chunks(2) {
        let (name, value) = pair[1].split_once('=').expect("name=value");
        runtime.set_param(name, value).expect("set param");
    }
    let n = (size.0 * size.1) as usize;
    let c = ["R", "G", "B", "A"].map(|a| channel(exr, &format!("ViewLayer.Combined.{a}")));
    let bytes = |floats: &mut dyn Iterator<Item = f32>| floats.flat_map(f32::to_le_bytes).collect::<Vec<u8>>();
    let colour = bytes(&mut (0..n).flat_map(|i| c.map(|ch| ch[i])));
    let colour = texture(wgpu::TextureFormat::Rgba32Float, size, &colour, 16);
    let depth = bytes(&mut channel(exr, "ViewLayer.Depth.Z").iter().copied());
    let depth = texture(wgpu::TextureFormat::R32Float, size, &depth, 4);
    let view = |t: &wgpu::Texture| t.create_view(&Default::default());
    runtime
        .set_input(
            "color_in",
            &view(&colour),
            SourceConvention::Color(ColorEncoding::Linear),
        )
        .expect("colour");
    runtime
        .set_input(
            "depth_in",
            &view(&depth),
            SourceConvention::Depth(DepthConvention::CYCLES),
        )
        .expect("depth");
    let objects = runtime.add_scene(&scene);
    let target = g.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("lines over"),
        size: wgpu::Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let lights = Lights::default();
    let frame = Frame {
        camera: &scene.camera,
        objects: &objects,
        lights: &lights,
        time_s: 0.0,
        frame_index: 0,
        eye: 0,
    };
    let mut encoder = g.device.create_command_encoder(&Default::default());
    runtime
        .render(&mut encoder, &frame, Target::View(&view(&target)))
        .unwrap_or_else(|e| panic!("{:?}", e.diagnostics()));
    g.queue.submit([encoder.finish()]);
    npr_runner::readback::read_texture(
        &g.device,
        &g.queue,
        &target,
        size.0,
        size.1,
        npr_abi::Format::Rgba8unorm,
        "lines over",
    )
    .expect("read back")
    .to_rgba8()
    .into_raw()
}
