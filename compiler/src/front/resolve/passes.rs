//! Resolve of pass declarations: the body (outputs, lets, settings per
//! kind), the pass modifiers and the vertex modifiers.
use super::*;

impl Resolver<'_> {
    // ---------------------------------------------------------------- passes

    pub(super) fn pass_body(&mut self, id: PassId, p: &ast::PassDecl) {
        self.current_pass = Some(id);
        let kind = match p.kind.kind.name.as_str() {
            "render" => {
                let tag = self.scene_or_tag(p, "a render pass draws one set of objects");
                PassKind::Render {
                    tag,
                    view: PassView::Camera,
                    vertex: VertexModifiers::default(),
                    depth: PassDepth::Own,
                }
            }
            "image" => {
                let mut inputs = Vec::new();
                for a in self.plain_kind_args(p, "a pass") {
                    match self.names.get(&a.name).copied() {
                        Some((Symbol::Pass(pid), _)) => inputs.push(pid),
                        _ => {
                            let passes: Vec<String> = self.ir.passes.iter().map(|p| p.name.clone()).collect();
                            let mut d = Diagnostic::error(codes::UNKNOWN_NAME, format!("no pass named `{}`", a.name))
                                .with_primary(a.span, "not a pass");
                            if let Some(s) = did_you_mean(&a.name, passes.iter().map(String::as_str)) {
                                d = d.with_help(format!("did you mean `{s}`?"));
                            }
                            self.error(d);
                        }
                    }
                }
                PassKind::Image { inputs, schedule: None }
            }
            "compute" => self.compute_kind(p),
            "lines" => self.lines_kind(p),
            other => {
                let kinds = ["render", "image", "compute", "lines"];
                let mut d = Diagnostic::error(codes::UNKNOWN_NAME, format!("unknown pass kind `{other}`"))
                    .with_primary(p.kind.kind.span, "not a pass kind");
                d = match did_you_mean(other, kinds) {
                    Some(s) => d.with_help(format!("did you mean `{s}`?")),
                    None => d.with_help(
                        "passes are `render(scene)`, `image(inputs...)`, `compute(domain)` or `lines(scene)`",
                    ),
                };
                self.error(d);
                PassKind::Image {
                    inputs: Vec::new(),
                    schedule: None,
                }
            }
        };
        self.draws_objects = kind.draws_objects();
        self.has_object = kind.has_object();
        self.in_image_pass = matches!(kind, PassKind::Image { .. });
        let scale = match &p.scale {
            None => 1.0,
            Some(e) => {
                let sid = self.expr(e);
                match self.const_scalar(sid, "a pass scale") {
                    Some(s) if s > 0.0 && s <= 4.0 => s,
                    Some(s) => {
                        self.error(
                            Diagnostic::error(codes::OUT_OF_RANGE, "pass scale out of range")
                                .with_primary(e.span, format!("{s} is outside (0, 4]"))
                                .with_help("a scale is relative to the output size, e.g. `scale 1/2`"),
                        );
                        1.0
                    }
                    None => 1.0,
                }
            }
        };
        let mut kind = kind;
        self.pass_modifiers(&mut kind, p);
        self.vertex_modifiers(&mut kind, p);
        let mut clear = [0.0, 0.0, 0.0, 0.0];
        let mut depth_seen = None;
        let mut schedule_seen = None;
        let mut line_settings_seen = Vec::new();
        for s in &p.body.settings {
            match s.key.name.as_str() {
                "depth" => self.depth_setting(&mut kind, s, &mut depth_seen),
                "schedule" => self.schedule_setting(&mut kind, s, &mut schedule_seen),
                key if lines::LINE_SETTINGS.contains(&key) => match &mut kind {
                    PassKind::Lines(l) => self.line_setting(l, s, &mut line_settings_seen),
                    _ => self.error(
                        Diagnostic::error(codes::BAD_ARGUMENT, format!("`{key}` is a setting of lines passes"))
                            .with_primary(s.key.span, format!("this is a {} pass", kind.name()))
                            .with_help("edges and their shape are drawn by `pass ink: lines(scene) { ... }`"),
                    ),
                },
                "count" | "seed" => self.sample_setting(&mut kind, s),
                "clear" => {
                    let cid = self.expr(&s.value);
                    if let Some(v) = self.const_values(cid) {
                        match v.len() {
                            1 => clear = [v[0], v[0], v[0], 1.0],
                            4 => clear = [v[0], v[1], v[2], v[3]],
                            3 => clear = [v[0], v[1], v[2], 1.0],
                            n => self.error(
                                Diagnostic::error(codes::TYPE_MISMATCH, "`clear` must be a colour")
                                    .with_primary(s.value.span, format!("this has {n} components")),
                            ),
                        }
                    }
                }
                other => {
                    let mut d = Diagnostic::error(codes::BAD_ARGUMENT, format!("unknown pass setting `{other}`"))
                        .with_primary(s.key.span, "not a pass setting");
                    let known = ["clear", "depth", "schedule", "count", "seed"]
                        .into_iter()
                        .chain(lines::LINE_SETTINGS);
                    d = match did_you_mean(other, known) {
                        Some(k) => d.with_help(format!("did you mean `{k}`?")),
                        None if matches!(kind, PassKind::Lines(_)) => d.with_help(format!(
                            "lines passes take `clear`, `depth: test(pass)` and {}",
                            lines::LINE_SETTINGS.map(|k| format!("`{k}`")).join(", ")
                        )),
                        None => d.with_help("pass settings are: `clear: #rrggbb`, `depth: keep`, `depth: test(pass)`, in image passes `schedule: naive | auto | tiled`, and in `compute(samples)` passes `count: n` and `seed: n`"),
                    };
                    self.error(d)
                }
            }
        }
        self.line_set_colors = None;
        match &mut kind {
            PassKind::Lines(lines) => {
                self.line_sets(lines, p);
                if !lines.sets.is_empty() {
                    self.line_set_colors = Some(lines.sets.iter().map(|s| s.color).collect());
                }
            }
            _ => {
                if let Some(set) = p.body.line_sets.first() {
                    self.error(
                        Diagnostic::error(codes::MISPLACED_LINE_SET, "a line set outside a lines pass")
                            .with_primary(set.name.span, format!("in a {} pass", kind.name()))
                            .with_help(
                                "line sets belong in `pass ink: lines(scene) { set outline { edges: silhouette } }`",
                            ),
                    );
                }
            }
        }
        let compute_domain = match &kind {
            PassKind::Compute { domain, .. } => Some(*domain),
            PassKind::Render { .. } | PassKind::Image { .. } | PassKind::Lines(_) => None,
        };
        match compute_domain {
            Some(_) => self.states_in_scope(id, p),
            None => self.refuse_compute_statements(p),
        }
        self.scopes.push(Vec::new());
        let mut lets = Vec::new();
        for l in &p.body.lets {
            let v = self.expr(&l.value);
            lets.push(Let {
                name: l.name.name.clone(),
                value: v,
                span: l.span,
            });
            if let Some(scope) = self.scopes.last_mut() {
                scope.push((l.name.name.clone(), v));
            }
        }
        if p.body.outputs.len() > MAX_OUTPUTS_PER_PASS {
            self.error(
                Diagnostic::error(codes::LIMIT_EXCEEDED, "too many outputs in one pass")
                    .with_primary(p.body.outputs[MAX_OUTPUTS_PER_PASS].span, "one too many")
                    .with_help(format!(
                        "a pass can write at most {MAX_OUTPUTS_PER_PASS} targets (the colour attachment limit); split it into two passes"
                    )),
            );
        }
        let mut outputs = Vec::new();
        let mut seen: Vec<&str> = Vec::new();
        if let (Some(domain), PassKind::Compute { values, .. }) = (compute_domain, &mut kind) {
            *values = self.compute_values(domain, p);
            self.check_value_names(values);
        }
        let targets = if compute_domain.is_some() {
            &[][..]
        } else {
            &p.body.outputs[..]
        };
        for o in targets.iter().take(MAX_OUTPUTS_PER_PASS) {
            if seen.contains(&o.name.name.as_str()) {
                self.error(
                    Diagnostic::error(
                        codes::DUPLICATE_NAME,
                        format!("output `{}` is declared twice", o.name.name),
                    )
                    .with_primary(o.name.span, "declared again here"),
                );
            }
            seen.push(&o.name.name);
            let format = match Format::parse(&o.format.name) {
                Some(f) => f,
                None => {
                    let names = Format::ALL.iter().map(|(n, _)| *n);
                    let mut d = Diagnostic::error(
                        codes::UNKNOWN_TYPE,
                        format!("unknown texture format `{}`", o.format.name),
                    )
                    .with_primary(o.format.span, "not a target format");
                    d = match did_you_mean(&o.format.name, names) {
                        Some(s) => d.with_help(format!("did you mean `{s}`?")),
                        None => d.with_help(format!(
                            "formats are: {}",
                            Format::ALL.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
                        )),
                    };
                    self.error(d);
                    Format::Rgba8unorm
                }
            };
            let value = self.expr(&o.value);
            let blend = self.output_blend(o, format);
            outputs.push(PassOutput {
                name: o.name.name.clone(),
                format,
                value,
                blend,
                span: o.span,
            });
        }
        self.scopes.pop();
        let pass = &mut self.ir.passes[id.0 as usize];
        pass.kind = kind;
        pass.scale = scale;
        pass.clear = clear;
        pass.lets = lets;
        pass.outputs = outputs;
        self.current_pass = None;
        self.line_set_colors = None;
        self.draws_objects = false;
        self.has_object = false;
        self.in_image_pass = false;
        self.states.clear();
    }

    /// `view(...)` and other modifiers after the pass kind.
    pub(super) fn pass_modifiers(&mut self, kind: &mut PassKind, p: &ast::PassDecl) {
        for m in &p.modifiers {
            match (m.key.name.as_str(), &m.value.kind, &mut *kind) {
                ("view", ast::ExprKind::Name(n), PassKind::Render { view, .. })
                    if n.name == "light" || n.name == "camera" =>
                {
                    *view = if n.name == "light" {
                        PassView::Light
                    } else {
                        PassView::Camera
                    };
                }
                ("view", _, _) => self.error(
                    Diagnostic::error(
                        codes::BAD_ARGUMENT,
                        "`view(...)` takes `camera` or `light` on a render pass",
                    )
                    .with_primary(m.span, "not a view of a render pass")
                    .with_help("write `pass depth: render(casters) view(light) { ... }`"),
                ),
                _ => self.error(
                    Diagnostic::error(
                        codes::BAD_ARGUMENT,
                        format!("unsupported pass modifier `{}`", m.key.name),
                    )
                    .with_primary(m.span, "not supported yet")
                    .with_help(
                        "render passes take `view(light)`; stereo pass modifiers are reserved for a later version",
                    ),
                ),
            }
        }
    }

    /// `vertex { ... }`: only render passes have a vertex shader of their own.
    pub(super) fn vertex_modifiers(&mut self, kind: &mut PassKind, p: &ast::PassDecl) {
        for s in &p.body.vertex {
            let slot = match (s.key.name.as_str(), &mut *kind) {
                ("inflate", PassKind::Render { vertex, .. }) => Some(&mut vertex.inflate),
                (
                    "shadow_warp",
                    PassKind::Render {
                        view: PassView::Light,
                        vertex,
                        ..
                    },
                ) => Some(&mut vertex.shadow_warp),
                _ => None,
            };
            match slot {
                Some(slot) => {
                    self.in_vertex = true;
                    *slot = Some(self.expr(&s.value));
                    self.in_vertex = false;
                }
                None => self.error(
                    Diagnostic::error(codes::BAD_ARGUMENT, format!("unknown vertex modifier `{}`", s.key.name))
                        .with_primary(s.key.span, "not a vertex modifier")
                        .with_help("render passes support `vertex { inflate: 2px }`; `view(light)` passes also `shadow_warp: k`"),
                ),
            }
        }
    }
}
