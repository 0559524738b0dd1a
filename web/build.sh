#!/usr/bin/env bash
# Build the npr-web package into web/pkg/ (or the directory given):
# the compiler for wasm32-unknown-unknown, bound by wasm-bindgen (`--target
# web`: an ES module and its .d.ts), and npr.js, the module a page imports.
# Needs the wasm32 target and wasm-bindgen-cli at the version Cargo.lock
# pins: `./setup.sh --tests` installs both.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-web/pkg}"
want=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
have=$(wasm-bindgen --version 2>/dev/null | awk '{ print $2 }' || true)
if [ "$have" != "$want" ]; then
  echo "web/build.sh: wasm-bindgen $want is needed (found: ${have:-none}); run ./setup.sh --tests, or: cargo install --locked wasm-bindgen-cli --version $want" >&2
  exit 1
fi
cargo build --target wasm32-unknown-unknown --release -p npr-web
target_dir=$(cargo metadata --format-version 1 --no-deps --offline | sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
wasm-bindgen --target web --out-dir "$out" "$target_dir/wasm32-unknown-unknown/release/npr_web.wasm"
cp web/js/npr.js web/js/npr.d.ts "$out/"
echo "web/build.sh: built $out ($(wc -c < "$out/npr_web_bg.wasm") bytes of WebAssembly)"
