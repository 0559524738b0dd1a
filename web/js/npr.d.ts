// The types of npr.js: the generated npr_web.d.ts, with `Style.compile`
// made async (it waits for a fresh instance after a trap).
import type { Style as CompiledStyle, NprFiles, NprCompileOptions } from "./npr_web.js";
export type { ShaderModule, NprFiles, NprCompileOptions, NprDiagnostic, NprError, NprLabel } from "./npr_web.js";

/** Load the WebAssembly module; `wasm` may name its URL. */
export default function init(wasm?: string | URL): Promise<void>;

/** A compiled style (see npr_web.d.ts). */
export type Style = CompiledStyle;
export declare const Style: {
  /** Compile `source`; throws an `NprError` when it does not compile. */
  compile(source: string, files?: NprFiles, options?: NprCompileOptions): Promise<CompiledStyle>;
};
