// The page side of tests/general/web_package.rs, evaluated in a headless
// Chromium over DevTools on a page served from 127.0.0.1: it imports the
// npr-web package (`/pkg/npr.js`, as web/build.sh writes it), fetches the
// example files the Rust side names from `/examples/`, and defines
// `window.nprWeb`, whose functions return plain JSON for the Rust side to
// compare with the native compiler's output.
(async () => {
  const npr = await import("/pkg/npr.js");
  await npr.default();

  // The files a style may name, fetched once: `.npr` as text, the rest as bytes.
  const files = {};
  const loadFiles = async (paths) => {
    for (const path of paths) {
      const reply = await fetch(`/examples/${path}`);
      if (!reply.ok) throw new Error(`fetch /examples/${path}: ${reply.status}`);
      files[path] = path.endsWith(".npr") ? await reply.text() : new Uint8Array(await reply.arrayBuffer());
    }
    return Object.keys(files).length;
  };

  // What a thrown value was: an NprError's fields, or how it is not one.
  const describe = (e) => ({
    isNprError: e instanceof Error && e.name === "NprError",
    isTrap: e instanceof WebAssembly.RuntimeError,
    code: e.code ?? null,
    file: e.file ?? null,
    line: e.line ?? null,
    column: e.column ?? null,
    message: String(e.message ?? e),
    diagnostics: e.diagnostics ?? null,
  });

  // Compile `source` named `name`: its modules and manifest, or the error.
  const compile = async (name, source, options = {}) => {
    try {
      const style = await npr.Style.compile(source, files, { name, ...options });
      return {
        ok: true,
        modules: style.modules.map((m) => [m.file, m.wgsl]),
        manifest: style.manifestJson,
        warnings: style.warnings,
      };
    } catch (e) {
      return { ok: false, error: describe(e) };
    }
  };

  window.nprWeb = {
    loadFiles,
    // The example `name` (relative to examples/), fetched and compiled.
    async compileExample(name) {
      const source = await (await fetch(`/examples/${name}`)).text();
      return compile(name, source);
    },
    compile,
    // Milliseconds per compile of the example `name`, over `runs` compiles
    // after one to warm up.
    async timeExample(name, runs) {
      const source = await (await fetch(`/examples/${name}`)).text();
      await npr.Style.compile(source, files, { name });
      const start = performance.now();
      for (let i = 0; i < runs; i++) await npr.Style.compile(source, files, { name });
      return (performance.now() - start) / runs;
    },
    // `setParam` of a style compiled with `keepParams`: the manifest's
    // entry for `param` after each value, or the error of the refused one.
    async setParams(name, param, values) {
      const source = await (await fetch(`/examples/${name}`)).text();
      const style = await npr.Style.compile(source, files, { name, keepParams: true });
      const out = [];
      for (const value of values) {
        try {
          style.setParam(param, value);
          const entry = JSON.parse(style.manifestJson).params.find((p) => p.name === param);
          out.push({ ok: true, default: entry.default });
        } catch (e) {
          out.push({ ok: false, error: describe(e) });
        }
      }
      return out;
    },
    // A panic inside npr: what the caller sees, and whether the module
    // compiles again afterwards.
    async panicThenCompile(name) {
      let seen;
      try {
        await npr.__nprPanicForTests();
        seen = { threw: false };
      } catch (e) {
        seen = { threw: true, ...describe(e) };
      }
      const source = await (await fetch(`/examples/${name}`)).text();
      return { seen, after: await compile(name, source) };
    },
  };
  return "ready";
})();
