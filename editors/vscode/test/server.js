// Drives `npr lsp` (the binary given as the first argument) with
// vscode-jsonrpc, the JSON-RPC library vscode-languageclient speaks through,
// as the extension's client would: initialize, open an example, wait for
// its diagnostics (none), hover an operator, shut down and exit.
"use strict";

const { spawn } = require("child_process");
const fs = require("fs");
const path = require("path");
const rpc = require("vscode-jsonrpc/node");

const npr = process.argv[2];
const style = path.resolve(process.argv[3]);
if (!npr || !style) throw new Error("usage: node test/server.js NPR STYLE.npr");
const uri = "file://" + style.split("/").map(encodeURIComponent).join("/");
const text = fs.readFileSync(style, "utf8");

function fail(message) {
  console.error(message);
  process.exit(1);
}

async function main() {
  const child = spawn(npr, ["lsp"], { stdio: ["pipe", "pipe", "inherit"] });
  const exited = new Promise((resolve) => child.on("exit", (code) => resolve(code)));
  const connection = rpc.createMessageConnection(
    new rpc.StreamMessageReader(child.stdout),
    new rpc.StreamMessageWriter(child.stdin)
  );
  const diagnostics = new Promise((resolve) =>
    connection.onNotification("textDocument/publishDiagnostics", (p) => {
      if (p.uri === uri) resolve(p.diagnostics);
    })
  );
  connection.listen();
  const init = await connection.sendRequest("initialize", { processId: process.pid, rootUri: null, capabilities: {} });
  if (!init.capabilities.hoverProvider || !init.capabilities.completionProvider) fail("capabilities: " + JSON.stringify(init));
  connection.sendNotification("initialized", {});
  connection.sendNotification("textDocument/didOpen", { textDocument: { uri, languageId: "npr", version: 1, text } });
  const diags = await diagnostics;
  if (diags.length !== 0) fail("diagnostics for an example that compiles: " + JSON.stringify(diags));
  const at = text.indexOf("toon(");
  if (at < 0) fail("the style calls no `toon`");
  const before = text.slice(0, at).split("\n");
  const position = { line: before.length - 1, character: before[before.length - 1].length + 1 };
  const hover = await connection.sendRequest("textDocument/hover", { textDocument: { uri }, position });
  if (!hover || !hover.contents.value.includes("toon(x: float")) fail("hover: " + JSON.stringify(hover));
  await connection.sendRequest("shutdown");
  connection.sendNotification("exit");
  const code = await exited;
  if (code !== 0) fail("npr lsp exited with " + code);
  console.log("ok: initialize, diagnostics, hover, shutdown through vscode-jsonrpc");
  process.exit(0);
}

main().catch((e) => fail(String(e && e.stack ? e.stack : e)));
