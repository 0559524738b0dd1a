// The npr VS Code extension: starts `npr lsp` (the `npr.path` setting) over
// stdio for .npr files and styles' test files (`*.tests.toml`, diagnostics
// only). Highlighting comes from syntaxes/npr.tmLanguage.json.
"use strict";

const vscode = require("vscode");
const { LanguageClient, TransportKind } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const command = vscode.workspace.getConfiguration("npr").get("path") || "npr";
  const serverOptions = { command, args: ["lsp"], transport: TransportKind.stdio };
  const clientOptions = {
    documentSelector: [
      { scheme: "file", language: "npr" },
      { scheme: "untitled", language: "npr" },
      { scheme: "file", pattern: "**/*.tests.toml" },
    ],
  };
  client = new LanguageClient("npr", "npr language server", serverOptions, clientOptions);
  context.subscriptions.push({ dispose: () => client && client.stop() });
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
