//! The expressions a pass evaluates, grouped by what needs them
//! ([`Pass::roots`]): the one definition that the pass graph (what a pass
//! reads), pruning (what a live pass keeps), the checks of vertex
//! modifiers and the emitter (what a vertex shader evaluates) share, so
//! that a new kind of root is added in one place.

use super::{ExprId, Ir, Pass, PassId, PassKind};

/// The roots of one pass, by what needs them.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct PassRoots {
    /// Each output's value, in output order.
    pub outputs: Vec<ExprId>,
    /// `vertex { ... }` of a render pass, in the order its vertex shader
    /// evaluates them: needed whenever the pass runs, also for its depth
    /// alone.
    pub vertex: Vec<ExprId>,
    /// A lines pass's shape settings, which the runner evaluates on the
    /// CPU: needed whenever the pass runs.
    pub settings: Vec<ExprId>,
    /// Each per-object value of a compute pass (its value, then a state's
    /// first value), in slot order.
    pub values: Vec<Vec<ExprId>>,
    /// The ID target read of a compute pass over pixels: needed by every
    /// value (the pass runs over that target's pixels).
    pub key: Option<ExprId>,
}

impl PassRoots {
    /// Every root, outputs first: what the pass may read.
    pub fn all(&self) -> Vec<ExprId> {
        let mut roots = self.outputs.clone();
        roots.extend(&self.vertex);
        roots.extend(self.values.iter().flatten());
        roots.extend(self.key);
        roots.extend(&self.settings);
        roots
    }
}

impl Pass {
    /// The expressions this pass evaluates, by what needs them.
    pub fn roots(&self) -> PassRoots {
        let mut roots = PassRoots {
            outputs: self.outputs.iter().map(|o| o.value).collect(),
            ..PassRoots::default()
        };
        match &self.kind {
            PassKind::Render { vertex, .. } => roots.vertex = vertex.roots(),
            PassKind::Image { .. } => {}
            PassKind::Compute { key, values, .. } => {
                roots.values = values.iter().map(|v| v.roots()).collect();
                roots.key = *key;
            }
            PassKind::Lines(lines) => {
                roots.settings = lines.shape.roots().to_vec();
                for set in &lines.sets {
                    roots.settings.extend(set.shape.roots());
                }
                roots.settings.sort_unstable();
                roots.settings.dedup();
            }
        }
        roots
    }
}

impl Ir {
    /// Expressions pass `pid`'s shaders evaluate once scheduled: its own
    /// ([`Pass::roots`]) and the values of the targets it computes in its
    /// tiles (`schedule/recompute.rs`), whose reads are its reads.
    pub fn scheduled_roots(&self, pid: PassId) -> Vec<ExprId> {
        let mut roots = self.pass(pid).roots().all();
        for (t, r) in &self.recomputed {
            if r.reader == pid {
                roots.push(self.pass(t.pass).outputs[t.output as usize].value);
            }
        }
        roots
    }
}
