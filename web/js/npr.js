// npr.js: the module a page imports (web/build.sh copies it beside the
// module wasm-bindgen generates, npr_web.js). It is that module's API with
// one difference: a panic inside npr, which in WebAssembly is a trap (a
// `WebAssembly.RuntimeError`, since panics abort there), comes back as an
// `NprError` with code E9001 and the panic's message, like any other
// error; the module is then loaded afresh (a trapped instance may hold
// broken state), so the next call works. Styles compiled before the trap
// belong to the old instance: compile them again.
//
//   import init, { Style } from "./npr.js";
//   await init();
//   const style = await Style.compile(source, files, { name: "toon.npr" });

const PANIC = Symbol.for("npr.panic");
let bindings = null;
let generation = 0;
let wasmUrl = null;

// Loads and instantiates the generated module: the first time as it is,
// after a trap under a new URL, which gives a new module record (and so a
// new instance) for the same files.
async function load() {
  const url = new URL("./npr_web.js", import.meta.url);
  if (generation > 0) url.searchParams.set("instance", String(generation));
  const module = await import(url.href);
  await module.default({ module_or_path: wasmUrl ?? new URL("./npr_web_bg.wasm", import.meta.url) });
  bindings = module;
}

// Settles when the current instance is loaded (a fresh one after a trap).
let ready = null;

/** Load the WebAssembly module; `wasm` may name its URL. */
export default async function init(wasm) {
  if (wasm !== undefined) wasmUrl = wasm;
  if (ready === null) ready = load();
  await ready;
}

// An NprError (as the Rust side makes them) for a trap.
function trapError(trap) {
  const panic = globalThis[PANIC];
  delete globalThis[PANIC];
  const message = `error[E9001]: internal error: npr panicked: ${panic ?? trap.message}`;
  const error = new Error(message);
  error.name = "NprError";
  Object.assign(error, { code: "E9001", file: null, line: null, column: null });
  error.diagnostics = [
    { severity: "error", code: "E9001", message, help: "this is a bug in npr, not in your style; please report it with the style", notes: [], labels: [], rendered: message },
  ];
  return error;
}

// Runs `call` on the current bindings; a trap becomes an NprError (thrown)
// and the module is loaded afresh before the next call.
async function guarded(call) {
  if (ready === null) throw new Error("npr: call `await init()` first");
  await ready;
  try {
    return call(bindings);
  } catch (e) {
    if (!(e instanceof WebAssembly.RuntimeError)) throw e;
    const error = trapError(e);
    generation += 1;
    // The next call waits for the fresh instance.
    ready = load();
    throw error;
  }
}

/** The compiler's entry point (`Style.compile` of npr_web.d.ts, made async
 * so that it can wait for a fresh instance after a trap). */
export const Style = {
  compile(source, files, options) {
    return guarded((b) => b.Style.compile(source, files, options));
  },
};

/** For the browser test of the trap handling only. */
export function __nprPanicForTests() {
  return guarded((b) => b.__nprPanicForTests());
}
