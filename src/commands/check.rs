//! `npr check`: parse and check a style (with its `--set`s and the texture
//! files it names) and print its diagnostics; nothing is written. With
//! `--ranges`, each target's proved value range (issue 49).

use crate::cli::CheckArgs;
use crate::printer::check_options;
use npr_diag::exit::{EXIT_OK, EXIT_USER};
use npr_diag::printer::MessageFormat;
use npr_diag::printer::Printer;
use npr_diag::SourceMap;

pub fn run(args: &CheckArgs, printer: &Printer) -> i32 {
    let mut sources = SourceMap::new();
    let opts = match check_options(&args.paths, &args.style, args.scene.as_deref(), &mut sources, printer) {
        Ok(o) => o,
        Err(code) => return code,
    };
    match crate::set_params::compile(&args.style, &args.set, &mut sources, &opts, printer) {
        Ok(c) => {
            printer.diagnostics(&c.warnings, &sources);
            let texture_errors =
                npr_test::texture_files::texture_file_errors(&c, npr_runner::texture_file::Depth::Decode);
            if !texture_errors.is_empty() {
                printer.diagnostics(&texture_errors, &sources);
                return EXIT_USER;
            }
            if args.ranges {
                print!("{}", c.ranges_text(&sources));
            }
            if printer.format == MessageFormat::Human {
                eprintln!(
                    "ok: style \"{}\": {} pass(es), {} target(s)",
                    c.manifest.style,
                    c.manifest.passes.len(),
                    c.manifest.targets.len()
                );
            }
            EXIT_OK
        }
        Err(code) => code,
    }
}
