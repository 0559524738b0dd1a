// npr studio page: renders the server's `state` events (no polling, no
// build step, nothing fetched but this server's own routes).
"use strict";
const $ = (id) => document.getElementById(id);
let state = null;
let selected = null;      // target index shown large; null = the output
let shown = { frame: -1, target: -1 };
let pixels = null;        // { w, h, data: Float32Array (rgba) } of the shown target
let controlsKey = "";
let playing = null;
let orbit = null;         // the page's orbit camera { yaw, pitch, zoom }, or null: the scene's
let drag = null;

function post(path, body) {
  return fetch(path, { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) });
}

function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === "class") e.className = v; else if (k.startsWith("on")) e.addEventListener(k.slice(2), v); else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

const events = new EventSource("/events");
events.addEventListener("state", (e) => apply(JSON.parse(e.data)));
events.onerror = () => setStatus("disconnected: reconnecting…", "error");

function setStatus(text, cls) { const s = $("status"); s.textContent = text; s.className = "status " + (cls || ""); }

function apply(s) {
  state = s;
  $("files").textContent = s.style + " on " + s.scene;
  const errors = (s.diagnostics || []).filter((d) => d.severity === "error");
  if (errors.length) setStatus(errors.length + " error(s): showing the last good image", "error");
  else if (s.frame) setStatus("frame " + s.frame.id, "ok");
  else setStatus("rendering…");
  $("notice").textContent = s.notice || "";
  renderDiagnostics(s.diagnostics || []);
  renderControls(s.params || [], s.param_error);
  renderView(s);
  renderTimings(s.frame);
}

function renderDiagnostics(diags) {
  const box = $("diagnostics");
  box.replaceChildren(...diags.map((d) => {
    const l = (d.labels || []).find((x) => x.primary) || (d.labels || [])[0];
    const where = l ? `${l.file}:${l.line}:${l.column}` : "";
    return el("div", { class: "diag " + d.severity, "data-code": d.code },
      el("div", {}, el("strong", {}, `${d.severity}[${d.code}]`), " ", d.message, " ", el("span", { class: "where" }, where)),
      el("pre", {}, d.rendered || ""));
  }));
}

function writtenNumber(p) { return parseFloat(p.literal); }

function renderControls(params, paramError) {
  const key = JSON.stringify(params.map((p) => [p.name, p.control, p.range_written]));
  if (key !== controlsKey) {
    controlsKey = key;
    $("controls").replaceChildren(...params.map(buildControl));
  }
  for (const p of params) {
    const row = document.querySelector(`.param[data-name="${p.name}"]`);
    if (!row) continue;
    const input = row.querySelector(".input");
    if (p.control === "gradient") updateGradient(input, p);
    else if (input && document.activeElement !== input) setInput(input, p);
    row.querySelector(".value").textContent = p.literal;
    const err = paramError && paramError.name === p.name ? paramError.message + (paramError.help ? " (" + paramError.help + ")" : "") : "";
    row.querySelector(".error").textContent = err;
  }
}

function setInput(input, p) {
  if (p.control === "bool") input.checked = p.literal === "true";
  else if (p.control === "color") input.value = p.literal.slice(0, 7);
  else if (p.control === "enum" || p.control === "range" || p.control === "vector") input.value = p.literal;
  else input.value = writtenNumber(p);
}

function literalOf(input, p) {
  if (p.control === "bool") return input.checked ? "true" : "false";
  if (p.control === "float" || p.control === "int" || p.control === "unit") return input.value + p.suffix;
  return input.value;
}

// ---- gradient: a ramp strip with stops to add, move (drag or type) and recolour.
// Its value is `--set` text, `0:#000000, 0.5:#ff8800, 1:#ffffff`; the server
// types it (E0206 for bad stops) and re-renders through the kept uniform.

function parseStops(text) {
  return text.split(",").map((s) => {
    const [pos, colour] = s.trim().split(":");
    return { pos: parseFloat(pos), colour: colour.trim() };
  });
}

function stopsText(stops) { return stops.map((s) => `${+s.pos.toFixed(4)}:${s.colour}`).join(", "); }

// `#rrggbb[aa]` as CSS `rgba(...)`, so a transparent stop shows as one.
function cssColour(c) {
  const n = (i) => parseInt(c.slice(i, i + 2), 16);
  const a = c.length > 7 ? n(7) / 255 : 1;
  return `rgba(${n(1)}, ${n(3)}, ${n(5)}, ${a})`;
}

function rampCss(stops, constant) {
  const parts = [];
  stops.forEach((s, i) => {
    parts.push(`${cssColour(s.colour)} ${s.pos * 100}%`);
    // Constant mode: each colour holds until the next stop.
    if (constant && i + 1 < stops.length) parts.push(`${cssColour(s.colour)} ${stops[i + 1].pos * 100}%`);
  });
  return `linear-gradient(to right, ${parts.join(", ")})`;
}

function buildGradient(p) {
  const g = el("div", { class: "input gradient" });
  g.stops = parseStops(p.literal);
  g.selected = 0;
  g.constant = (p.default || [])[1] > 0.5;
  const strip = el("div", { class: "strip" });
  const pos = el("input", { type: "number", class: "stop-pos", min: 0, max: 1, step: 0.01, title: "the selected stop's position, 0 to 1" });
  const colour = el("input", { type: "color", class: "stop-colour", title: "the selected stop's colour" });
  const send = () => post("/param", { name: p.name, literal: stopsText(g.stops) });
  // Keep the moved stop selected when the order changes.
  const reorder = () => {
    const moved = g.stops[g.selected];
    g.stops.sort((a, b) => a.pos - b.pos);
    g.selected = g.stops.indexOf(moved);
  };
  pos.addEventListener("change", () => {
    g.stops[g.selected].pos = Math.min(1, Math.max(0, parseFloat(pos.value) || 0));
    reorder(); drawGradient(g); send();
  });
  colour.addEventListener("input", () => {
    const old = g.stops[g.selected].colour;
    g.stops[g.selected].colour = colour.value + old.slice(7);  // keep the stop's alpha
    drawGradient(g); send();
  });
  const add = el("button", { class: "add-stop", title: "add a stop halfway to the next one", onclick: () => {
    const i = g.selected, s = g.stops;
    const [a, b] = i + 1 < s.length ? [s[i], s[i + 1]] : [s[i - 1] || s[i], s[i]];
    g.stops.splice(s.indexOf(b), 0, { pos: (a.pos + b.pos) / 2, colour: s[i].colour });
    g.selected = g.stops.indexOf(g.stops.find((x) => x.pos === (a.pos + b.pos) / 2));
    drawGradient(g); send();
  } }, "add stop");
  const remove = el("button", { class: "remove-stop", title: "remove the selected stop", onclick: () => {
    if (g.stops.length < 2) return;
    g.stops.splice(g.selected, 1);
    g.selected = Math.min(g.selected, g.stops.length - 1);
    drawGradient(g); send();
  } }, "remove");
  // Drag a stop along the strip; sent when released.
  strip.addEventListener("pointerdown", (e) => {
    const handle = e.target.closest(".stop");
    if (!handle) return;
    g.selected = Number(handle.dataset.i);
    g.dragging = true;
    g.moved = false;
    strip.setPointerCapture(e.pointerId);
    drawGradient(g);
  });
  strip.addEventListener("pointermove", (e) => {
    if (!g.dragging) return;
    const r = strip.getBoundingClientRect();
    g.stops[g.selected].pos = Math.min(1, Math.max(0, (e.clientX - r.left) / r.width));
    g.moved = true;
    reorder(); drawGradient(g);
  });
  // A click only selects; a drag sends the moved stop.
  strip.addEventListener("pointerup", () => { if (g.dragging) { g.dragging = false; if (g.moved) send(); } });
  g.append(strip, el("div", { class: "stop-row" }, "stop ", pos, colour, add, remove));
  drawGradient(g);
  return g;
}

function drawGradient(g) {
  const strip = g.querySelector(".strip");
  strip.style.background = rampCss(g.stops, g.constant);
  strip.replaceChildren(...g.stops.map((s, i) => el("div", {
    class: "stop" + (i === g.selected ? " selected" : ""), "data-i": i,
    style: `left: ${s.pos * 100}%; background: ${cssColour(s.colour)}`, title: `${s.pos}: ${s.colour}`,
  })));
  const pos = g.querySelector(".stop-pos"), colour = g.querySelector(".stop-colour");
  if (document.activeElement !== pos) pos.value = g.stops[g.selected].pos;
  colour.value = g.stops[g.selected].colour.slice(0, 7);
}

// The server's value (a reset, a file change) unless the user is editing it.
function updateGradient(g, p) {
  if (!g || g.dragging || g.contains(document.activeElement)) return;
  if (stopsText(g.stops) === stopsText(parseStops(p.literal))) return;
  g.stops = parseStops(p.literal);
  g.selected = Math.min(g.selected, g.stops.length - 1);
  drawGradient(g);
}

function buildControl(p) {
  let input;
  const send = () => post("/param", { name: p.name, literal: literalOf(input, p) });
  if (p.control === "bool") input = el("input", { type: "checkbox", class: "input", onchange: send });
  else if (p.control === "enum") input = el("select", { class: "input", onchange: send }, ...p.enum_variants.map((v) => el("option", { value: v }, v)));
  else if (p.control === "color") input = el("input", { type: "color", class: "input", oninput: send });
  else if (p.control === "gradient") input = buildGradient(p);
  else if (p.range_written && (p.control === "float" || p.control === "int" || p.control === "unit"))
    input = el("input", { type: "range", class: "input", min: p.range_written[0], max: p.range_written[1], step: p.step, oninput: send });
  else if (p.control === "float" || p.control === "int" || p.control === "unit")
    input = el("input", { type: "number", class: "input", step: p.step, onchange: send });
  else input = el("input", { type: "text", class: "input", onchange: send });
  if (p.unused) input.disabled = true;
  const copy = el("button", { title: "copy as a --set argument", onclick: () => {
    const text = `--set '${p.name}=${state.params.find((q) => q.name === p.name).literal}'`;
    (navigator.clipboard ? navigator.clipboard.writeText(text) : Promise.reject()).catch(() => window.prompt("copy:", text));
  } }, "--set");
  const write = el("button", { title: "write this value into the .npr file as the default", onclick: () => post("/param/write", { name: p.name }) }, "write");
  const reset = el("button", { title: "back to the file's value", onclick: () => post("/param/reset", { name: p.name }) }, "reset");
  const title = (p.doc || p.name) + (p.unused ? " (not used by the output)" : "");
  return el("div", { class: "param" + (p.unused ? " unused" : ""), "data-name": p.name, title },
    el("div", { class: "name" }, p.name, " ", el("span", { class: "where" }, p.ty)),
    el("div", { class: "row" }, input, el("span", { class: "value" }), copy, write, reset),
    el("div", { class: "error" }));
}

function renderView(s) {
  orbit = s.view.orbit || null;
  $("camera-reset").disabled = !orbit;
  const f = s.frame;
  if (!f) return;
  const eyeBox = $("eye-box");
  eyeBox.hidden = !s.view.stereo;
  $("eye").value = String(s.view.eye);
  if (document.activeElement !== $("time")) $("time").value = s.view.time;
  $("time-value").textContent = s.view.time.toFixed(3) + " s";
  if (selected !== null && selected >= f.targets.length) selected = null;
  const target = selected === null ? f.output : selected;
  if (shown.frame !== f.id) {
    $("thumbs").replaceChildren(...f.targets.map((t) => el("div", {
      class: "thumb" + (t.index === target ? " selected" : ""), "data-index": t.index,
      title: `${t.name} (${t.format})`, onclick: () => { selected = t.index; draw(state.frame, t.index); markThumbs(t.index); },
    }, el("img", { src: `/frame/${f.id}/${t.index}.png`, alt: t.name }), t.name)));
  }
  if (shown.frame !== f.id || shown.target !== target) draw(f, target);
}

function markThumbs(target) {
  for (const t of document.querySelectorAll(".thumb")) t.classList.toggle("selected", Number(t.dataset.index) === target);
}

// Draws overlap (each awaits its fetch, and the server encodes a target on
// its first request): only the one asked for last may show, or an older
// frame finishing late would replace a newer one on screen.
let drawSeq = 0;

async function draw(f, target) {
  const t = f.targets[target];
  const seq = ++drawSeq;
  const res = await fetch(`/frame/${f.id}/${target}.f32`);
  if (!res.ok) return; // a newer frame replaced it; its event is on the way
  const data = new Float32Array(await res.arrayBuffer());
  if (seq !== drawSeq) return; // a later draw was asked for meanwhile
  pixels = { w: t.width, h: t.height, data, float: t.float, channels: t.format };
  shown = { frame: f.id, target };
  $("target-name").textContent = `${t.name} · ${t.format} · ${t.width}×${t.height}` + (target === f.output ? " · output" : "");
  paint();
  const view = $("view");
  view.dataset.frame = f.id;
  view.dataset.target = target;
  document.body.dataset.shownFrame = f.id;
  document.body.dataset.shownTarget = target;
}

// Draw the shown target: float targets scaled by 2^exposure; R/G/B toggles,
// or alpha alone. One-channel targets show as grey, as `npr render` writes them.
function paint() {
  if (!pixels) return;
  const { w, h, data } = pixels;
  const view = $("view");
  if (view.width !== w || view.height !== h) { view.width = w; view.height = h; view.style.width = Math.max(w, 512) + "px"; }
  const ctx = view.getContext("2d");
  const img = ctx.createImageData(w, h);
  const gain = pixels.float ? Math.pow(2, parseFloat($("exposure").value)) : 1;
  const on = [$("ch-r").checked, $("ch-g").checked, $("ch-b").checked];
  const alphaOnly = $("ch-a").checked;
  const grey = /^(R8|R16|R32)/i.test(pixels.channels);
  const q = (v) => Math.round(Math.min(Math.max(Number.isFinite(v) ? v * gain : 0, 0), 1) * 255);
  // Written texel by texel: an array per texel (`set([...])`) made a 512²
  // frame's paint cost tens of milliseconds.
  const out = img.data;
  for (let i = 0, o = 0; i < w * h; i++, o += 4) {
    const r = data[o], g = grey ? r : data[o + 1], b = grey ? r : data[o + 2], a = grey ? 1 : data[o + 3];
    if (alphaOnly) { const v = q(a); out[o] = v; out[o + 1] = v; out[o + 2] = v; out[o + 3] = 255; continue; }
    out[o] = on[0] ? q(r) : 0; out[o + 1] = on[1] ? q(g) : 0; out[o + 2] = on[2] ? q(b) : 0;
    out[o + 3] = Math.round(Math.min(Math.max(a, 0), 1) * 255);
  }
  ctx.putImageData(img, 0, 0);
}

function renderTimings(f) {
  if (!f) return;
  const rows = [["compile (scene + style)", f.compile_ms], ["render + read-back", f.render_ms]];
  for (const p of f.passes || []) rows.push(["  pass " + p.name + " (GPU)", p.gpu_ms]);
  $("timings").replaceChildren(el("table", {}, ...rows.map(([k, v]) => el("tr", {}, el("td", {}, k), el("td", {}, v.toFixed(2) + " ms")))),
    el("div", { class: "where" }, f.device + (f.passes ? "" : " · no timestamp queries: per-pass GPU time unavailable")));
}

$("view").addEventListener("mousemove", (e) => {
  if (!pixels) return;
  const r = e.target.getBoundingClientRect();
  const x = Math.floor((e.clientX - r.left) * pixels.w / r.width), y = Math.floor((e.clientY - r.top) * pixels.h / r.height);
  if (x < 0 || y < 0 || x >= pixels.w || y >= pixels.h) return;
  const i = 4 * (y * pixels.w + x);
  const v = Array.from(pixels.data.slice(i, i + 4)).map((c) => c.toFixed(4));
  $("readout").textContent = `(${x}, ${y}) = ${v.join(", ")}`;
});
// Orbit/zoom: a drag turns the camera about the scene camera's target
// (yaw, pitch in degrees), the wheel scales its distance; the server
// renders with it until "reset to the scene's camera".
const DEG_PER_PX = 0.5;
function sendOrbit(o) { orbit = o; $("camera-reset").disabled = !o; post("/view", { orbit: o }); }
$("view").addEventListener("mousedown", (e) => {
  const o = orbit || { yaw: 0, pitch: 0, zoom: 1 };
  drag = { x: e.clientX, y: e.clientY, yaw: o.yaw, pitch: o.pitch, zoom: o.zoom };
  e.preventDefault();
});
window.addEventListener("mousemove", (e) => {
  if (!drag) return;
  sendOrbit({
    yaw: drag.yaw - (e.clientX - drag.x) * DEG_PER_PX,
    pitch: Math.max(-89, Math.min(89, drag.pitch + (e.clientY - drag.y) * DEG_PER_PX)),
    zoom: drag.zoom,
  });
});
window.addEventListener("mouseup", () => { drag = null; });
$("view").addEventListener("wheel", (e) => {
  const o = orbit || { yaw: 0, pitch: 0, zoom: 1 };
  sendOrbit({ yaw: o.yaw, pitch: o.pitch, zoom: Math.max(0.05, Math.min(20, o.zoom * Math.exp(e.deltaY * 0.001))) });
  e.preventDefault();
}, { passive: false });
$("camera-reset").addEventListener("click", () => sendOrbit(null));
for (const id of ["exposure", "ch-r", "ch-g", "ch-b", "ch-a"]) $(id).addEventListener("input", paint);
$("time").addEventListener("input", () => post("/view", { time: parseFloat($("time").value) }));
$("eye").addEventListener("change", () => post("/view", { eye: parseInt($("eye").value, 10) }));
$("play").addEventListener("click", () => {
  if (playing) { clearInterval(playing); playing = null; $("play").textContent = "play"; return; }
  $("play").textContent = "pause";
  const fps = Math.max(1, parseFloat($("fps").value) || 24);
  playing = setInterval(() => {
    const t = ((state ? state.view.time : 0) + 1 / fps) % parseFloat($("time").max);
    post("/view", { time: t });
  }, 1000 / fps);
});
