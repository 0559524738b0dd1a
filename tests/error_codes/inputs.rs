//! Host inputs (issue 47): E0420 for each way an input file cannot be
//! used, and the compile errors of a bad `input(...)` declaration.

use super::*;

/// A style over two inputs: colour and depth.
const TWO_INPUTS: &str = "style \"Case\"\ntexture beauty = input(color, display)\ntexture z = input(depth)\npass p: image() {\n  out c: rgba8unorm = vec4(beauty.rgb * z.r, 1.0)\n}\noutput p.c\n";

/// `dir/case.npr` holding `text`; its path as an argument.
fn style_file(dir: &Path, text: &str) -> String {
    let path = dir.join("case.npr");
    std::fs::write(&path, text).expect("write style");
    path.display().to_string()
}

fn png(dir: &Path, name: &str, (w, h): (u32, u32)) -> String {
    let path = dir.join(name);
    image::RgbaImage::from_pixel(w, h, image::Rgba([128, 128, 128, 255]))
        .save(&path)
        .expect("write png");
    path.display().to_string()
}

/// An EXR of un-prefixed R G B A channels, R = `r(x, y)`.
fn exr(dir: &Path, name: &str, (w, h): (usize, usize), r: impl Fn(usize, usize) -> f32 + Sync) -> String {
    let path = dir.join(name);
    exr::prelude::write_rgba_file(&path, w, h, |x, y| (r(x, y), 0.0f32, 0.0f32, 1.0f32)).expect("write exr");
    path.display().to_string()
}

#[test]
fn e0420_an_input_the_style_reads_is_not_given() {
    let dir = scratch("e0420");
    let style = style_file(&dir, TWO_INPUTS);
    let beauty = format!("beauty={}", png(&dir, "beauty.png", (8, 8)));
    check("E0420", cli_errors(&["render", &style, "--input", &beauty], &dir));
}

#[test]
fn e0420_an_exr_without_the_layer() {
    let dir = scratch("e0420_layer");
    let style = style_file(&dir, TWO_INPUTS);
    let file = exr(&dir, "passes.exr", (8, 8), |_, _| 1.0);
    let (d, r) = cli_errors(&["render", &style, "--inputs", &file], &dir);
    assert!(r.contains("no layer `Combined`") && r.contains("--map"), "{r}");
    check_case("E0420", "E0420_missing_layer", (d, r));
}

#[test]
fn e0420_inputs_of_two_sizes() {
    let dir = scratch("e0420_size");
    let style = style_file(&dir, TWO_INPUTS);
    let beauty = format!("beauty={}", png(&dir, "beauty.png", (8, 8)));
    let z = format!("z={}", exr(&dir, "z.exr", (8, 6), |_, _| 2.0));
    let (d, r) = cli_errors(&["render", &style, "--input", &beauty, "--input", &z], &dir);
    assert!(r.contains("8x6") && r.contains("8x8"), "{r}");
    check_case("E0420", "E0420_sizes", (d, r));
}

#[test]
fn e0420_a_non_finite_depth() {
    let dir = scratch("e0420_nan");
    let style = style_file(&dir, TWO_INPUTS);
    let beauty = format!("beauty={}", png(&dir, "beauty.png", (8, 8)));
    let z = format!(
        "z={}",
        exr(&dir, "z.exr", (8, 8), |x, y| if (x, y) == (3, 5) {
            f32::INFINITY
        } else {
            2.0
        })
    );
    let (d, r) = cli_errors(&["render", &style, "--input", &beauty, "--input", &z], &dir);
    assert!(r.contains("(3, 5)") && r.contains("`z`"), "{r}");
    check_case("E0420", "E0420_non_finite_depth", (d, r));
}

#[test]
fn e0420_a_file_that_is_not_an_image() {
    let dir = scratch("e0420_text");
    let style = style_file(&dir, TWO_INPUTS);
    let text = dir.join("beauty.png");
    std::fs::write(&text, "not a png").expect("write");
    let beauty = format!("beauty={}", text.display());
    let (d, r) = cli_errors(&["render", &style, "--input", &beauty], &dir);
    assert!(r.contains("`beauty`") && r.contains("beauty.png"), "{r}");
    check_case("E0420", "E0420_not_an_image", (d, r));
}

#[test]
fn an_unknown_input_kind_says_which_it_meant() {
    let (d, r) = compile_errors(
        &style("texture n = input(normals, view)\npass p: image() {\n  out c: rgba8unorm = n\n}\noutput p.c\n"),
        Path::new("."),
    );
    assert!(r.contains("did you mean `normal`?"), "{r}");
    check_case("E0103", "E0103_input_kind", (d, r));
}

#[test]
fn a_colour_input_says_whether_it_is_linear_or_display() {
    let (d, r) = compile_errors(
        &style("texture c = input(color)\npass p: image() {\n  out o: rgba8unorm = c\n}\noutput p.o\n"),
        Path::new("."),
    );
    assert!(r.contains("`linear`") && r.contains("`display`"), "{r}");
    check_case("E0103", "E0103_input_color_encoding", (d, r));
}

#[test]
fn a_host_input_is_not_a_per_object_texture() {
    let (d, r) = compile_errors(
        &style(
            "object param t: texture = input(depth)\npass p: render(scene) {\n  out o: rgba8unorm = t\n}\noutput p.o\n",
        ),
        Path::new("."),
    );
    check_case("E0103", "E0103_input_per_object", (d, r));
}

/// A two-frame sequence `b_0000.png`, `b_0001.png` of `sizes`, and one depth
/// file for all frames; the `--input` arguments naming them.
fn sequence(dir: &Path, sizes: [(u32, u32); 2]) -> [String; 2] {
    for (frame, size) in sizes.into_iter().enumerate() {
        png(dir, &format!("b_{frame:04}.png"), size);
    }
    [
        format!("beauty={}", dir.join("b_{frame}.png").display()),
        format!("z={}", exr(dir, "z.exr", (8, 8), |_, _| 2.0)),
    ]
}

#[test]
fn e0421_a_frame_of_an_input_sequence_is_missing() {
    let dir = scratch("e0421");
    let style = style_file(&dir, TWO_INPUTS);
    let [beauty, z] = sequence(&dir, [(8, 8), (8, 8)]);
    let out = dir.join("out_{frame}.png").display().to_string();
    let args = [
        "render", &style, "--input", &beauty, "--input", &z, "--frames", "0..4", "-o", &out,
    ];
    let (d, r) = cli_errors(&args, &dir);
    assert!(
        r.contains("`beauty`") && r.contains("b_0002.png") && r.contains("2, 3"),
        "{r}"
    );
    // Found before the first frame: nothing was written.
    assert!(!dir.join("out_0000.png").exists(), "a frame was written: {r}");
    check("E0421", (d, r));
}

#[test]
fn e0422_a_frame_of_another_size_than_the_first() {
    let dir = scratch("e0422");
    let style = style_file(&dir, TWO_INPUTS);
    let [beauty, z] = sequence(&dir, [(8, 8), (8, 6)]);
    let out = dir.join("out_{frame}.png").display().to_string();
    let args = [
        "render", &style, "--input", &beauty, "--input", &z, "--frames", "0..2", "-o", &out,
    ];
    let (d, r) = cli_errors(&args, &dir);
    assert!(
        r.contains("frame 1") && r.contains("8x6") && r.contains("b_0000.png"),
        "{r}"
    );
    assert!(!dir.join("out_0000.png").exists(), "a frame was written: {r}");
    check("E0422", (d, r));
}

#[test]
fn e0502_an_input_pattern_that_is_not_a_frame_number() {
    let dir = scratch("e0502_pattern");
    let style = style_file(&dir, TWO_INPUTS);
    let beauty = format!("beauty={}", dir.join("b_{frame:4}.png").display());
    let (d, r) = cli_errors(&["render", &style, "--input", &beauty, "--frames", "0..2"], &dir);
    assert!(r.contains("{frame:4}") && r.contains("{frame:0N}"), "{r}");
    check_case("E0502", "E0502_input_pattern", (d, r));
}
