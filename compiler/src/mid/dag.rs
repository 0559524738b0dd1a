//! Build the pass DAG: which pass reads which, a topological execution
//! order, and a clear error for any dependency cycle. A pass reads another
//! through a target, or through its depth (`depth: test(other)`).

use crate::ir::*;
use npr_diag::{codes, Diagnostic, Span};

#[derive(Debug, Clone, Default)]
pub struct PassGraph {
    /// For each pass, the passes it reads, with the span of one read of each.
    pub reads: Vec<Vec<(PassId, Span)>>,
    /// Passes in execution order. Empty when there is a cycle.
    pub order: Vec<PassId>,
}

pub fn build(ir: &Ir, diags: &mut Vec<Diagnostic>) -> PassGraph {
    let n = ir.passes.len();
    let mut reads: Vec<Vec<(PassId, Span)>> = vec![Vec::new(); n];
    for (pi, pass) in ir.passes.iter().enumerate() {
        // A depth test reads the tested pass's depth buffer: it runs after it.
        if let Some((tested, span)) = pass.depth_test() {
            reads[pi].push((tested, span));
        }
        for id in ir.reachable(&pass.roots().all()) {
            let e = ir.expr(id);
            let read = e
                .kind
                .target_read()
                .map(|t| t.pass)
                .or(e.kind.value_read().map(|(p, _)| p));
            if let Some(p) = read {
                if !reads[pi].iter().any(|(q, _)| *q == p) {
                    reads[pi].push((p, e.span));
                }
            }
        }
    }
    // Depth-first search with colours; a grey node reached again closes a cycle.
    let mut colour = vec![0u8; n];
    let mut order = Vec::new();
    let mut cycle_found = false;
    for start in 0..n {
        if colour[start] != 0 || cycle_found {
            continue;
        }
        let mut stack: Vec<(usize, usize)> = vec![(start, 0)];
        colour[start] = 1;
        while let Some((node, next)) = stack.pop() {
            if next < reads[node].len() {
                stack.push((node, next + 1));
                let (dep, span) = reads[node][next];
                let d = dep.0 as usize;
                match colour[d] {
                    0 => {
                        colour[d] = 1;
                        stack.push((d, 0));
                    }
                    1 => {
                        let mut path: Vec<usize> = stack.iter().map(|(p, _)| *p).collect();
                        if let Some(pos) = path.iter().position(|p| *p == d) {
                            path.drain(..pos);
                        }
                        let names: Vec<&str> = path.iter().map(|p| ir.passes[*p].name.as_str()).collect();
                        let is_depth =
                            |r: usize, t: usize| ir.passes[r].depth_test().is_some_and(|(p, _)| p.0 as usize == t);
                        let reads_what = |r: usize, t: usize| {
                            let (r_name, t_name) = (&ir.passes[r].name, &ir.passes[t].name);
                            if is_depth(r, t) {
                                format!("`{r_name}` tests against `{t_name}`'s depth")
                            } else {
                                format!("`{r_name}` reads `{t_name}`")
                            }
                        };
                        let mut diag = Diagnostic::error(
                            codes::PASS_CYCLE,
                            format!(
                                "passes depend on each other in a cycle: {} -> {}",
                                names.join(" -> "),
                                ir.passes[d].name
                            ),
                        )
                        .with_primary(span, format!("{} here", reads_what(node, d)));
                        for w in path.windows(2) {
                            if let Some((_, s)) = reads[w[0]].iter().find(|(p, _)| p.0 as usize == w[1]) {
                                diag = diag.with_secondary(*s, reads_what(w[0], w[1]));
                            }
                        }
                        // `previous(...)` breaks a target read, not a depth
                        // test: name a read edge of the cycle (one exists, as
                        // a tested pass keeps its depth, so tests no other).
                        let mut edges = path.windows(2).map(|w| (w[0], w[1])).chain([(node, d)]);
                        let (r, t) = edges.rfind(|(r, t)| !is_depth(*r, *t)).unwrap_or((node, d));
                        let (reader, read) = (&ir.passes[r].name, &ir.passes[t].name);
                        diags.push(diag.with_help(format!(
                            "a pass can only read this frame's targets of passes that run before it; \
                             compute one of these values in a separate pass, or read the previous \
                             frame's value with `previous({read}.<target>)` in `{reader}`"
                        )));
                        cycle_found = true;
                        break;
                    }
                    _ => {}
                }
            } else {
                colour[node] = 2;
                order.push(PassId(node as u32));
            }
        }
    }
    if cycle_found {
        order.clear();
    }
    PassGraph { reads, order }
}
