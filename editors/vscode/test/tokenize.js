// Tokenizes every .npr file under examples/ (or the files given) with the
// extension's TextMate grammar, as VS Code does (vscode-textmate +
// vscode-oniguruma), and fails on any non-blank token that has no scope
// but the file's own (`source.npr`) or that the grammar marks illegal.
"use strict";

const fs = require("fs");
const path = require("path");
const vsctm = require("vscode-textmate");
const oniguruma = require("vscode-oniguruma");

const here = __dirname;
const repo = path.resolve(here, "..", "..", "..");
const grammarPath = path.join(here, "..", "syntaxes", "npr.tmLanguage.json");

function exampleFiles(dir) {
  const out = [];
  for (const entry of fs.readdirSync(dir, { withFileTypes: true })) {
    const full = path.join(dir, entry.name);
    if (entry.isDirectory()) out.push(...exampleFiles(full));
    else if (entry.name.endsWith(".npr")) out.push(full);
  }
  return out.sort();
}

async function main() {
  const wasm = fs.readFileSync(path.join(path.dirname(require.resolve("vscode-oniguruma")), "onig.wasm")).buffer;
  await oniguruma.loadWASM(wasm);
  const registry = new vsctm.Registry({
    onigLib: Promise.resolve({
      createOnigScanner: (patterns) => new oniguruma.OnigScanner(patterns),
      createOnigString: (s) => new oniguruma.OnigString(s),
    }),
    loadGrammar: async (scopeName) =>
      scopeName === "source.npr"
        ? vsctm.parseRawGrammar(fs.readFileSync(grammarPath, "utf8"), grammarPath)
        : null,
  });
  const grammar = await registry.loadGrammar("source.npr");
  const files = process.argv.length > 2 ? process.argv.slice(2) : exampleFiles(path.join(repo, "examples"));
  if (files.length === 0) throw new Error("no .npr files to tokenize");
  const failures = [];
  let tokens = 0;
  const scopesSeen = new Set();
  for (const file of files) {
    const lines = fs.readFileSync(file, "utf8").split(/\r?\n/);
    let state = vsctm.INITIAL;
    lines.forEach((line, i) => {
      const r = grammar.tokenizeLine(line, state);
      for (const t of r.tokens) {
        const text = line.slice(t.startIndex, t.endIndex);
        tokens += 1;
        t.scopes.forEach((s) => scopesSeen.add(s));
        const unscoped = t.scopes.length === 1 && text.trim() !== "";
        const illegal = t.scopes.some((s) => s.startsWith("invalid."));
        if (unscoped || illegal) {
          failures.push(`${path.relative(repo, file)}:${i + 1}:${t.startIndex + 1}: ${unscoped ? "unscoped" : "illegal"} token ${JSON.stringify(text)}`);
        }
      }
      state = r.ruleStack;
    });
  }
  if (failures.length > 0) {
    console.error(`${failures.length} bad token(s):\n${failures.slice(0, 50).join("\n")}`);
    process.exit(1);
  }
  console.log(`ok: ${files.length} file(s), ${tokens} tokens, ${scopesSeen.size} scopes, none unscoped or illegal`);
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
