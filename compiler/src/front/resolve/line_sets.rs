//! Resolve the line sets of a `lines` pass (decision 0056):
//!
//! ```text
//! set outline { edges: silhouette | border, width: 3px, color: ink, priority: 1 }
//! set detail  { edges: crease(35deg) | material_boundary | intersection, tag: parts }
//! ```
//!
//! Each set has `edges:` (a union of edge types), optionally `tag:` (only
//! the pass's objects with that tag), `visibility:` (`visible`,
//! `hidden`, `hidden(n)` or `all`, by quantitative invisibility; decision
//! 0063), `dash:` (`6px` or `dashes(6px, 4px)`), `priority: n` (higher first; ties in the order
//! written), `color:` (what `line.color` is on its strips) and the pass's
//! shape settings (`width`, `amplitude`, `wavelength`, `phase`, `taper`),
//! each the pass's own where unset. The sets are sorted by priority here,
//! and a set whose every edge a set before it takes is refused (E0315).
//! `line.color` becomes a choice on `line.set` among the sets' colours.

use super::Resolver;
use crate::ir::*;
use npr_abi::lines::LineVisibility;
use npr_diag::diagnostic::did_you_mean;
use npr_diag::{codes, Diagnostic, Span};
use npr_dsl::ast::{self, BinOp, ExprKind as AK, UnitSuffix};
use npr_stdlib::Unit;

/// The edge types a set's `edges:` may name (Freestyle's names).
pub(super) const EDGE_TYPES: [&str; 6] = [
    "silhouette",
    "border",
    "crease",
    "material_boundary",
    "intersection",
    "marked",
];

/// The settings of a set besides `edges`.
const SET_SETTINGS: [&str; 10] = [
    "tag",
    "visibility",
    "dash",
    "priority",
    "color",
    "width",
    "amplitude",
    "wavelength",
    "phase",
    "taper",
];

/// What `line.color` is on strips of no set's colour: opaque black.
const DEFAULT_COLOR: [f64; 4] = [0.0, 0.0, 0.0, 1.0];

impl Resolver<'_> {
    /// The pass's `set` blocks, into `lines.sets` sorted by priority.
    pub(super) fn line_sets(&mut self, lines: &mut LinesKind, p: &ast::PassDecl) {
        if p.body.line_sets.is_empty() {
            return;
        }
        for s in &p.body.settings {
            if matches!(s.key.name.as_str(), "silhouettes" | "creases") {
                self.error(
                    Diagnostic::error(codes::MISPLACED_LINE_SET, format!("`{}` beside line sets", s.key.name))
                        .with_primary(s.key.span.to(s.value.span), "a pass-level edge selection")
                        .with_secondary(p.body.line_sets[0].name.span, "this pass draws its sets")
                        .with_help("a pass with sets draws what its sets select: move the edges into a set's `edges:`"),
                );
            }
        }
        let mut sets: Vec<LineSet> = Vec::new();
        for decl in &p.body.line_sets {
            if let Some(first) = sets.iter().find(|s| s.name == decl.name.name) {
                self.error(
                    Diagnostic::error(
                        codes::DUPLICATE_LINE_SET,
                        format!("two line sets are named `{}`", decl.name.name),
                    )
                    .with_primary(decl.name.span, "second set")
                    .with_secondary(first.span, "first set")
                    .with_help("rename one of them"),
                );
                continue;
            }
            sets.push(self.line_set(lines, decl));
        }
        // Highest priority first; the sort is stable, so ties keep the order written.
        sets.sort_by_key(|s| std::cmp::Reverse(s.priority));
        for (k, set) in sets.iter().enumerate() {
            if set.edges.is_empty() {
                continue; // reported where its `edges:` is
            }
            let covering = sets[..k].iter().find(|higher| {
                let (mine, theirs) = (
                    LineVisibility::qi_range(set.visibility),
                    LineVisibility::qi_range(higher.visibility),
                );
                // Sets of disjoint visibilities both draw an edge.
                let overlap = theirs.0 <= mine.1 && mine.0 <= theirs.1;
                (higher.tag.is_none() || higher.tag == set.tag) && overlap && higher.edges.covers(&set.edges)
            });
            if let Some(higher) = covering {
                self.error(
                    Diagnostic::error(
                        codes::EMPTY_LINE_SET,
                        format!("line set `{}` selects nothing", set.name),
                    )
                    .with_primary(set.span, "every edge it selects is drawn by a set before it")
                    .with_secondary(
                        higher.span,
                        "this set takes them (an edge is drawn once, by the higher set)",
                    )
                    .with_help("give it a higher `priority:`, or edge types or a `tag:` the other set does not take"),
                );
            }
        }
        lines.sets = sets;
        // The sets replace the pass-level selection: none is left to draw
        // apart from them (a runner that knew no sets would draw nothing,
        // not the default silhouettes).
        lines.edges = npr_abi::lines::LineEdges {
            silhouettes: false,
            crease_deg: None,
        };
    }

    fn line_set(&mut self, lines: &LinesKind, decl: &ast::LineSetDecl) -> LineSet {
        let mut set = LineSet {
            name: decl.name.name.clone(),
            span: decl.name.span,
            tag: None,
            edges: npr_abi::lines::EdgeTypes::default(),
            shape: lines.shape,
            color: None,
            priority: 0,
            visibility: None,
            dash: None,
        };
        match &decl.edges[..] {
            [] => self.error(
                Diagnostic::error(
                    codes::EMPTY_LINE_SET,
                    format!("line set `{}` selects nothing", set.name),
                )
                .with_primary(decl.name.span, "no `edges:`")
                .with_help(format!(
                    "add `edges: silhouette | crease(40deg)`; the edge types are {}",
                    quoted(&EDGE_TYPES)
                )),
            ),
            [union, more @ ..] => {
                set.edges = self.edge_union(union);
                for extra in more {
                    self.error(
                        Diagnostic::error(codes::DUPLICATE_NAME, "`edges` is set twice")
                            .with_primary(extra.span, "second `edges`")
                            .with_secondary(union.span, "first `edges`")
                            .with_help("join them into one union: `edges: silhouette | border`"),
                    );
                }
            }
        }
        let mut seen: Vec<(&str, Span)> = Vec::new();
        for s in &decl.settings {
            let key = s.key.name.as_str();
            let here = s.key.span.to(s.value.span);
            if let Some((_, first)) = seen.iter().find(|(k, _)| *k == key) {
                self.error(
                    Diagnostic::error(codes::DUPLICATE_NAME, format!("`{key}` is set twice"))
                        .with_primary(here, format!("second `{key}`"))
                        .with_secondary(*first, format!("first `{key}`")),
                );
                continue;
            }
            seen.push((key, here));
            match key {
                "edges" => self.error(
                    Diagnostic::error(codes::UNKNOWN_EDGE_TYPE, "`edges` is a union of edge types")
                        .with_primary(s.value.span, "not an edge type")
                        .with_help(format!(
                            "write `edges: silhouette | crease(40deg)`; the edge types are {}",
                            quoted(&EDGE_TYPES)
                        )),
                ),
                "tag" => match &s.value.kind {
                    AK::Name(n) => set.tag = Some(n.name.clone()),
                    _ => self.error(
                        Diagnostic::error(codes::BAD_ARGUMENT, "`tag` is a tag's name")
                            .with_primary(s.value.span, "not a name")
                            .with_help("write `tag: hero` to draw only the pass's objects tagged `hero`"),
                    ),
                },
                "visibility" => set.visibility = self.line_visibility(&s.value),
                "dash" => set.dash = self.line_dash(&s.value),
                "priority" => match &s.value.kind {
                    AK::Number { value, unit: None, .. } if value.fract() == 0.0 && value.abs() < 1e6 => {
                        set.priority = *value as i64
                    }
                    AK::Unary {
                        op: ast::UnOp::Neg,
                        operand,
                    } if matches!(&operand.kind, AK::Number { value, unit: None, .. } if value.fract() == 0.0 && value.abs() < 1e6) => {
                        if let AK::Number { value, .. } = &operand.kind {
                            set.priority = -(*value as i64);
                        }
                    }
                    _ => self.error(
                        Diagnostic::error(codes::BAD_ARGUMENT, "`priority` is a whole number")
                            .with_primary(s.value.span, "not a whole number")
                            .with_help("write `priority: 2`: a higher set draws an edge two sets select"),
                    ),
                },
                "color" => set.color = Some(self.expr(&s.value)),
                _ if set.shape.get_mut(key).is_some() => {
                    let value = self.expr(&s.value);
                    if let Some(slot) = set.shape.get_mut(key) {
                        *slot = value;
                    }
                }
                other => {
                    let mut d = Diagnostic::error(
                        codes::MISPLACED_LINE_SET,
                        format!("`{other}` is not a setting of a line set"),
                    )
                    .with_primary(s.key.span, "not a set setting");
                    d = match did_you_mean(other, SET_SETTINGS.iter().copied().chain(["edges"])) {
                        Some(k) => d.with_help(format!("did you mean `{k}`?")),
                        None => d.with_help(format!(
                            "a set takes `edges`, {}; `depth`, `clear` and outputs are the pass's",
                            quoted(&SET_SETTINGS)
                        )),
                    };
                    self.error(d);
                }
            }
        }
        set
    }

    /// `visible`, `hidden`, `hidden(n)` or `all` (decision 0063).
    fn line_visibility(&mut self, value: &ast::Expr) -> Option<LineVisibility> {
        let help = "write `visibility: visible` (no surface in front), `hidden` (one or more), \
                    `hidden(1)` (exactly one) or `all`";
        match &value.kind {
            AK::Name(n) => match n.name.as_str() {
                "visible" => return Some(LineVisibility::Visible),
                "hidden" => return Some(LineVisibility::Hidden),
                "all" => return Some(LineVisibility::All),
                _ => {}
            },
            AK::Call(call) if call.callee.name == "hidden" => {
                if let [ast::Arg {
                    name: None, value: n, ..
                }] = &call.args[..]
                {
                    if let AK::Number {
                        value: count,
                        unit: None,
                        ..
                    } = &n.kind
                    {
                        if count.fract() == 0.0 && (1.0..1e6).contains(count) {
                            return Some(LineVisibility::Behind(*count as u32));
                        }
                    }
                }
                self.error(
                    Diagnostic::error(codes::BAD_LINE_VISIBILITY, "`hidden(n)` counts surfaces")
                        .with_primary(value.span, "not one whole number from 1")
                        .with_help("write `hidden(1)`: the lines behind exactly one surface"),
                );
                return None;
            }
            _ => {}
        }
        let written = match &value.kind {
            AK::Name(n) => format!("`{}`", n.name),
            _ => "this".to_string(),
        };
        let mut d = Diagnostic::error(
            codes::BAD_LINE_VISIBILITY,
            format!("{written} is not a line visibility"),
        )
        .with_primary(value.span, "not a visibility");
        d = match &value.kind {
            AK::Name(n) => match did_you_mean(&n.name, ["visible", "hidden", "all"]) {
                Some(k) => d.with_help(format!("did you mean `{k}`? {help}")),
                None => d.with_help(help),
            },
            _ => d.with_help(help),
        };
        self.error(d);
        None
    }

    /// `dash: 6px` (as long as the gaps) or `dash: dashes(6px, 4px)`.
    fn line_dash(&mut self, value: &ast::Expr) -> Option<[f64; 2]> {
        let px = |e: &ast::Expr| match &e.kind {
            AK::Number {
                value,
                unit: Some(UnitSuffix::Px),
                ..
            } => Some(*value),
            _ => None,
        };
        let pattern = match &value.kind {
            AK::Call(call) if call.callee.name == "dashes" => match &call.args[..] {
                [ast::Arg {
                    name: None, value: on, ..
                }, ast::Arg {
                    name: None, value: off, ..
                }] => px(on).zip(px(off)).map(|(on, off)| [on, off]),
                _ => None,
            },
            _ => px(value).map(|on| [on, on]),
        };
        match pattern {
            Some([on, off]) if on > 0.0 && off > 0.0 && on.is_finite() && off.is_finite() => Some([on, off]),
            _ => {
                self.error(
                    Diagnostic::error(codes::BAD_LINE_DASH, "a dash is lengths in px over 0")
                        .with_primary(value.span, "not a dash pattern")
                        .with_help("write `dash: 6px` (dashes and gaps of 6px) or `dash: dashes(6px, 4px)` (6px drawn, 4px left out)"),
                );
                None
            }
        }
    }

    /// `silhouette | border | crease(35deg)` as edge types.
    fn edge_union(&mut self, union: &ast::EdgeUnion) -> npr_abi::lines::EdgeTypes {
        let mut edges = npr_abi::lines::EdgeTypes::default();
        for term in &union.terms {
            let name = term.name.name.as_str();
            if name != "crease" {
                if let Some(arg) = &term.arg {
                    self.error(
                        Diagnostic::error(codes::UNKNOWN_EDGE_TYPE, format!("`{name}` takes no argument"))
                            .with_primary(arg.span, "an argument")
                            .with_help(
                                "only `crease(angle)` takes one: the dihedral angle over which an edge is a crease",
                            ),
                    );
                    continue;
                }
            }
            match name {
                "silhouette" => edges.silhouette = true,
                "border" => edges.border = true,
                "material_boundary" => edges.material_boundary = true,
                "intersection" => edges.intersection = true,
                "marked" => edges.marked = true,
                "crease" => {
                    if let Some(deg) = self.crease_angle(term) {
                        edges.crease_deg = Some(edges.crease_deg.map_or(deg, |d: f64| d.min(deg)));
                    }
                }
                other => {
                    let mut d = Diagnostic::error(codes::UNKNOWN_EDGE_TYPE, format!("unknown edge type `{other}`"))
                        .with_primary(term.name.span, "not an edge type");
                    d = match did_you_mean(other, EDGE_TYPES) {
                        Some(k) => d.with_help(format!("did you mean `{k}`?")),
                        None => d.with_help(format!("the edge types are {}", quoted(&EDGE_TYPES))),
                    };
                    self.error(d);
                }
            }
        }
        edges
    }

    /// The angle of `crease(35deg)`, a dihedral angle in 0..180°.
    fn crease_angle(&mut self, term: &ast::EdgeTerm) -> Option<f64> {
        let help = "write `crease(35deg)`: edges whose faces turn by more than 35°";
        let Some(arg) = &term.arg else {
            self.error(
                Diagnostic::error(codes::BAD_CREASE_ANGLE, "`crease` needs an angle")
                    .with_primary(term.span, "no angle")
                    .with_help(help),
            );
            return None;
        };
        match &arg.kind {
            AK::Number {
                value,
                unit: Some(UnitSuffix::Deg),
                ..
            } if (0.0..=180.0).contains(value) => Some(*value),
            AK::Number {
                value,
                unit: Some(UnitSuffix::Deg),
                ..
            } => {
                self.error(
                    Diagnostic::error(codes::BAD_CREASE_ANGLE, "crease angle out of range")
                        .with_primary(arg.span, format!("{value}° is outside 0deg..180deg"))
                        .with_help("a dihedral angle is between 0° (every edge) and 180° (none)"),
                );
                None
            }
            _ => {
                self.error(
                    Diagnostic::error(codes::BAD_CREASE_ANGLE, "a crease threshold is an angle in `deg`")
                        .with_primary(arg.span, "not an angle in deg")
                        .with_help(help),
                );
                None
            }
        }
    }

    /// `line.color` or `line.set`, which only a lines pass with sets has.
    pub(super) fn line_set_value(&mut self, spelled: &str, span: Span) -> ExprId {
        match self.line_set_colors.clone() {
            Some(colors) if spelled == "line.color" => self.line_color(&colors, span),
            Some(_) => self
                .ir
                .add_typed(ExprKind::Builtin(Builtin::LineSet), Ty::Int, Unit::None, span),
            None => {
                self.error(
                    Diagnostic::error(codes::MISPLACED_LINE_SET, format!("`{spelled}` outside a line set"))
                        .with_primary(span, "this pass has no line sets")
                        .with_help(
                            "`line.color` is the colour of the set drawing a strip, `line.set` its index: \
                             they exist in a lines pass with `set name { edges: ..., color: ... }` blocks",
                        ),
                );
                self.ir.add(ExprKind::Error, span)
            }
        }
    }

    /// `line.color` in a pass with sets: the drawing set's `color:` (opaque
    /// black for a set without one), chosen on `line.set`.
    fn line_color(&mut self, colors: &[Option<ExprId>], span: Span) -> ExprId {
        let black = |r: &mut Self| {
            r.ir.add_typed(
                ExprKind::Const(Const::Vec(DEFAULT_COLOR.to_vec())),
                Ty::Vec4,
                Unit::None,
                span,
            )
        };
        let mut chosen = black(self);
        for (index, color) in colors.iter().enumerate().rev() {
            let value = match color {
                Some(c) => *c,
                None => black(self),
            };
            let set = self
                .ir
                .add_typed(ExprKind::Builtin(Builtin::LineSet), Ty::Int, Unit::None, span);
            let k = self
                .ir
                .add_typed(ExprKind::Const(Const::Int(index as i64)), Ty::Int, Unit::None, span);
            let cond = self.ir.add(
                ExprKind::Binary {
                    op: BinOp::Eq,
                    lhs: set,
                    rhs: k,
                },
                span,
            );
            chosen = self.ir.add(
                ExprKind::Select {
                    cond,
                    then: value,
                    otherwise: chosen,
                },
                span,
            );
        }
        chosen
    }
}

/// `a`, `b` and `c` as a list in prose.
fn quoted(names: &[&str]) -> String {
    names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
}
