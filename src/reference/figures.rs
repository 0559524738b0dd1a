//! Speed against error per operator, where a benchmark has it: the rows of
//! `npr bench ops` (`npr_lab::bench_ops`, MetaTexture and its extensions
//! against a plain `sample`) as committed in docs/PERFORMANCE.md. `npr doc`
//! runs no benchmark: it reads the committed table (a frame time depends on
//! the machine and its load; the reference must be the same on every run),
//! and gives each operator the rows whose style runs it, either by calling
//! it or through a specialization (`metatexture(…, skew: 0)` runs
//! `metatexture4`). A variant of `npr_lab::bench_ops::variants()` without a row
//! in the table is an error: the table is older than the benchmark.

/// The header of the `npr bench ops` table (`npr_lab::bench_ops::table`).
const HEADER: &str = "| variant | ms/frame | cost vs plain sample | scale error | anisotropy | contrast error |";

/// The committed `npr bench ops` table: its device line and rows.
pub struct Figures {
    /// "Device: …" above the table, as committed.
    device: String,
    /// (variant name, the row's cells after the name).
    rows: Vec<(String, Vec<String>)>,
}

impl Figures {
    /// The table in `performance` (docs/PERFORMANCE.md's text), or what is wrong with it.
    pub fn parse(performance: &str) -> Result<Figures, String> {
        let lines: Vec<&str> = performance.lines().collect();
        let at = lines
            .iter()
            .position(|l| l.trim() == HEADER)
            .ok_or_else(|| format!("no `npr bench ops` table (a line `{HEADER}`)"))?;
        let device = lines[..at]
            .iter()
            .rev()
            .find(|l| l.starts_with("Device:"))
            .map(|l| l.trim().to_string())
            .ok_or("no `Device:` line above the `npr bench ops` table")?;
        let rows = lines[at + 2..]
            .iter()
            .take_while(|l| l.starts_with('|'))
            .map(|l| {
                let cells: Vec<String> = l
                    .trim()
                    .trim_matches('|')
                    .split('|')
                    .map(|c| c.trim().to_string())
                    .collect();
                (cells[0].clone(), cells[1..].to_vec())
            })
            .collect();
        let figures = Figures { device, rows };
        for v in npr_lab::bench_ops::variants() {
            if figures.row(v.name).is_none() {
                return Err(format!(
                    "the `npr bench ops` table has no row for the variant \"{}\": run `npr bench ops` and update the table",
                    v.name
                ));
            }
        }
        Ok(figures)
    }

    fn row(&self, variant: &str) -> Option<&[String]> {
        self.rows
            .iter()
            .find(|(name, cells)| name == variant && cells.len() == 5)
            .map(|(_, cells)| cells.as_slice())
    }

    /// The Markdown of `op`'s figures, or "" when no benchmark runs it.
    pub fn markdown(&self, op: &npr_stdlib::Operator) -> String {
        let variants: Vec<_> = npr_lab::bench_ops::variants()
            .into_iter()
            .filter(|v| runs(&format!("{}{}", v.lets, v.read), op))
            .collect();
        if variants.is_empty() {
            return String::new();
        }
        let mut out = format!(
            "*Speed against error* (`npr bench ops`, the committed table of docs/PERFORMANCE.md, \"MetaTexture\": one render pass with only the texture read changed, \
             its fastest frame; errors in f64 on an analytic ground plane; {}):\n\n\
             | variant | ms/frame | cost vs plain sample | scale error | anisotropy | contrast error |\n|---|---:|---:|---:|---:|---:|\n",
            self.device.trim_end_matches('.')
        );
        for v in variants {
            if let Some(cells) = self.row(v.name) {
                out.push_str(&format!("| {} | {} |\n", v.name, cells.join(" | ")));
            }
        }
        out.push('\n');
        out
    }
}

/// Whether the style text `text` runs `op`: calls it, or calls an operator
/// with a specialization to it and writes that argument (`skew: 0`).
fn runs(text: &str, op: &npr_stdlib::Operator) -> bool {
    npr_stdlib::ops::style_calls(text, op.name)
        || npr_stdlib::all().iter().any(|from| {
            npr_stdlib::ops::style_calls(text, from.name)
                && from.specializations.iter().any(|s| {
                    s.use_operator == op.name
                        && text.contains(&format!("{}: {}", s.param, npr_compiler::describe::number(s.value)))
                })
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn op(name: &str) -> &'static npr_stdlib::Operator {
        npr_stdlib::all().iter().find(|o| o.name == name).expect("an operator")
    }

    #[test]
    fn a_variant_runs_what_it_calls_and_what_it_specializes_to() {
        let text = "metatexture(grain, uv, width: 48px, skew: 0)";
        assert!(runs(text, op("metatexture")));
        assert!(runs(text, op("metatexture4")));
        assert!(!runs(text, op("metatexture4_grad")));
        assert!(!runs("metatexture(grain, uv, skew: 4)", op("metatexture4")));
        assert!(!runs("sample_biased(t, uv)", op("sample")));
    }

    #[test]
    fn the_committed_table_has_every_variant() {
        let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/PERFORMANCE.md"))
            .expect("docs/PERFORMANCE.md");
        let f = Figures::parse(&text).expect("the table");
        assert!(f.device.starts_with("Device:"));
        assert!(f
            .markdown(op("metatexture4"))
            .contains("| 4-tap, derivative gradients |"));
        assert_eq!(f.markdown(op("toon")), "");
        assert!(Figures::parse("no table here").is_err());
    }
}
