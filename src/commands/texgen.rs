//! `npr texgen`: npr's own tileable noise (the generator `noise(...)`
//! textures use) or a painterly colour map, written as a PNG.

use crate::cli::TexgenArgs;
use npr_diag::exit::EXIT_OK;
use npr_diag::printer::Printer;
use npr_diag::writes::cannot_write;
use std::path::Path;

pub fn run(args: TexgenArgs, printer: &Printer) -> i32 {
    let TexgenArgs {
        out,
        size,
        octaves,
        seed,
        channels,
        frequency,
        kind,
        color,
    } = args;
    let kind = match crate::args::texgen_kind(&kind) {
        Ok(k) => k,
        Err(d) => return printer.fail(d),
    };
    let paint = kind == crate::args::TexgenKind::Paint;
    if let Err(code) = printer.check(crate::args::check_texgen(size, channels, octaves, frequency, paint)) {
        return code;
    }
    let gradient = match kind {
        crate::args::TexgenKind::Noise { gradient } => gradient,
        crate::args::TexgenKind::Paint => {
            return match crate::args::paint_color(color.as_deref()) {
                Ok(base) => texgen_paint(&out, size, seed, base, printer),
                Err(d) => printer.fail(d),
            }
        }
    };
    let spec = npr_abi::NoiseSpec {
        size,
        octaves,
        seed,
        gradient,
        channels,
        frequency,
    };
    let written = npr_runner::texgen::write_png16(&npr_runner::texgen::generate(&spec), &out);
    report_written(written, &out, &format!("{size}x{size}, {channels} channel(s)"), printer)
}

/// Say what `npr texgen` wrote, or why it could not: the exit code.
fn report_written(result: std::io::Result<()>, out: &Path, what: &str, printer: &Printer) -> i32 {
    match result {
        Ok(()) => {
            eprintln!("wrote {} ({what})", out.display());
            EXIT_OK
        }
        Err(e) => printer.fail(cannot_write(out, e)),
    }
}

/// `npr texgen --kind paint --color "#rrggbb"`: [`npr_runner::texgen::paint_map`] as an 8-bit PNG.
fn texgen_paint(out: &std::path::Path, size: u32, seed: u32, base: [f64; 3], printer: &Printer) -> i32 {
    let map = npr_runner::texgen::paint_map(size, base, seed);
    let image = image::RgbaImage::from_fn(map.width, map.height, |x, y| {
        image::Rgba(map.pixels[(y * map.width + x) as usize])
    });
    report_written(
        npr_runner::output::write_png8(&image, out),
        out,
        &format!("{size}x{size} paint map"),
        printer,
    )
}
