// The page side of tests/general/webgpu_portability.rs, evaluated in a
// headless Chromium over DevTools: each compiled style's shader modules go
// through the browser's own WebGPU (Dawn, its WGSL compiler Tint), on a
// device made with exactly the features and limits the style's manifest
// asks for, and each pass's pipelines are built from the layouts the
// manifest implies (written by the Rust side as WebGPU descriptors).
// Returns every problem (a compilation message of any type but `info`, a
// device that cannot be made, a pipeline WebGPU refuses), and the
// pipelines still compiling after `compileDeadlineMs`: valid, but their
// compilation still occupies the browser, so the caller restarts it.
window.nprCheck = async (styles, compileDeadlineMs) => {
  const problems = [];
  const slow = [];
  let checked = 0;
  for (const style of styles) {
    checked += 1;
    const report = (pass, what, message) => problems.push({ style: style.label, pass, what, message });
    // An adapter makes one device; each style gets a fresh one.
    const adapter = await navigator.gpu.requestAdapter();
    if (!adapter) {
      report("", "adapter", "navigator.gpu.requestAdapter() gave none");
      continue;
    }
    let device;
    try {
      device = await adapter.requestDevice({
        requiredFeatures: style.features,
        requiredLimits: style.limits,
      });
    } catch (e) {
      report("", "device", String(e));
      continue;
    }
    for (const pass of style.passes) {
      const module = device.createShaderModule({ code: pass.code, label: pass.shader });
      const info = await module.getCompilationInfo();
      for (const m of info.messages) {
        if (m.type !== "info") {
          report(pass.name, `${m.type} at ${pass.shader}:${m.lineNum}:${m.linePos}`, m.message);
        }
      }
      for (const p of pass.pipelines) {
        device.pushErrorScope("validation");
        let outcome;
        try {
          const bindGroupLayouts = p.groups.map((entries) => device.createBindGroupLayout({ entries }));
          const layout = device.createPipelineLayout({ bindGroupLayouts });
          // Async creation: Dawn validates the descriptor against the
          // module first and rejects at once; only a valid pipeline goes
          // on to SwiftShader's compiler, which may take minutes (so the
          // wait is bounded: past it the pipeline was valid, only slow).
          const pending = p.compute
            ? device.createComputePipelineAsync({
                layout,
                compute: { module, entryPoint: p.compute, constants: p.constants },
              })
            : device.createRenderPipelineAsync({
                layout,
                vertex: { module, entryPoint: p.vertex, buffers: p.buffers, constants: p.constants },
                fragment: { module, entryPoint: p.fragment, targets: p.targets, constants: p.constants },
                primitive: { topology: "triangle-list", cullMode: "none" },
                depthStencil: p.depthStencil ?? undefined,
              });
          const deadline = new Promise((done) => setTimeout(() => done("slow"), compileDeadlineMs));
          outcome = await Promise.race([pending.then(() => "built", (e) => e), deadline]);
        } catch (e) {
          outcome = e;
        }
        const error = await device.popErrorScope();
        if (error) {
          report(pass.name, `pipeline ${p.label}`, error.message);
        }
        if (outcome === "slow") {
          slow.push(`${style.label}, pass \`${pass.name}\`, pipeline ${p.label}`);
        } else if (outcome !== "built") {
          report(pass.name, `pipeline ${p.label}`, String(outcome?.message ?? outcome));
        }
      }
    }
    device.destroy();
    if (slow.length > 0) {
      break;
    }
  }
  return { problems, slow, checked };
};
"ready";
