//! A readable text dump of the IR (for `npr compile --dump-ir`).

use crate::ir::*;
use std::fmt::Write;

pub fn dump(ir: &Ir) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "style {:?}", ir.style_name);
    for (i, p) in ir.params.iter().enumerate() {
        let _ = writeln!(
            s,
            "param #{i} {} : {:?} {:?} default=e{} range={:?} keys={} per_object={}",
            p.name,
            p.ty,
            p.unit,
            p.default.0,
            p.range,
            p.keys.len(),
            p.per_object
        );
    }
    for (i, t) in ir.textures.iter().enumerate() {
        let _ = writeln!(s, "texture #{i} {} : {:?}", t.name, t.source);
    }
    for (i, p) in ir.passes.iter().enumerate() {
        let kind = match &p.kind {
            PassKind::Render {
                tag,
                view,
                vertex,
                depth,
            } => format!(
                "render({}) view={view:?} inflate={} shadow_warp={} depth={depth:?}",
                tag.as_deref().unwrap_or("scene"),
                expr_ref(vertex.inflate),
                expr_ref(vertex.shadow_warp)
            ),
            PassKind::Image { inputs, schedule } => {
                let names: Vec<&str> = inputs.iter().map(|i| ir.pass(*i).name.as_str()).collect();
                match schedule {
                    Some(s) => format!("image({}) schedule={}", names.join(", "), s.schedule.name()),
                    None => format!("image({})", names.join(", ")),
                }
            }
            PassKind::Compute { domain, tag, .. } => match tag {
                Some(t) => format!("compute({}, {t})", domain.name()),
                None => format!("compute({})", domain.name()),
            },
            PassKind::Lines(lines) => {
                let settings: Vec<String> = lines
                    .shape
                    .named()
                    .iter()
                    .map(|(n, e)| format!("{n}=e{}", e.0))
                    .collect();
                format!(
                    "lines({}) edges={:?} {} depth={:?}",
                    lines.tag.as_deref().unwrap_or("scene"),
                    lines.edges,
                    settings.join(" "),
                    lines.depth
                )
            }
        };
        let _ = writeln!(s, "pass #{i} {} : {kind} scale={}", p.name, p.scale);
        for l in &p.lets {
            let _ = writeln!(s, "  let {} = e{}", l.name, l.value.0);
        }
        for o in &p.outputs {
            let blend = match o.blend {
                npr_abi::manifest::Blend::Replace => String::new(),
                b => format!(" blend={}", b.name()),
            };
            let _ = writeln!(s, "  out {} : {} = e{}{blend}", o.name, o.format.name(), o.value.0);
        }
        for (slot, v) in p.kind.values().iter().enumerate() {
            let _ = writeln!(
                s,
                "  value #{slot} {} : {} {:?} = e{} first={}",
                v.name,
                v.ty.describe(),
                v.rule,
                v.value.0,
                expr_ref(v.first)
            );
        }
    }
    for (i, e) in ir.exprs.iter().enumerate() {
        let _ = writeln!(s, "e{i} : {:?} {:?} = {:?}", e.ty, e.unit, e.kind);
    }
    s
}

fn expr_ref(e: Option<ExprId>) -> String {
    e.map_or_else(|| "-".into(), |e| format!("e{}", e.0))
}
