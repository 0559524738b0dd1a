#!/usr/bin/env bash
# Set up a fresh Debian/Ubuntu machine for npr: a software Vulkan driver
# (Mesa lavapipe) when no Vulkan driver is installed, and a Rust toolchain
# check. Safe to run repeatedly.
set -euo pipefail

have_vulkan_icd() {
  ls /usr/share/vulkan/icd.d/*.json /etc/vulkan/icd.d/*.json 2>/dev/null | grep -q .
}

if ! have_vulkan_icd; then
  echo "setup: no Vulkan driver found; installing Mesa's software driver (mesa-vulkan-drivers)"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq mesa-vulkan-drivers libvulkan1 >/dev/null
fi

# The studio's browser test (tests/general/studio_browser.rs) drives Debian's
# Chromium headless over the DevTools protocol; no browser is downloaded.
if [ ! -x /usr/bin/chromium ]; then
  echo "setup: installing Chromium for the studio's browser test (apt: chromium)"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq chromium >/dev/null
fi

if ! command -v cargo >/dev/null 2>&1; then
  echo "setup: cargo not found; install Rust from your distribution or rustup" >&2
  exit 1
fi

# The VS Code extension's tests (tests/general/vscode_extension.rs) run its grammar
# with vscode-textmate and drive `npr lsp` with vscode-jsonrpc: Node.js and
# the extension's npm packages (pinned by editors/vscode/package-lock.json).
if ! command -v npm >/dev/null 2>&1; then
  echo "setup: installing Node.js and npm for the VS Code extension's tests (apt: nodejs npm)"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq nodejs npm >/dev/null
fi
if [ ! -d "$(dirname "$0")/editors/vscode/node_modules/vscode-textmate" ]; then
  echo "setup: npm ci in editors/vscode"
  (cd "$(dirname "$0")/editors/vscode" && npm ci --no-audit --no-fund --loglevel=error)
fi

# The Vulkan loader warns when XDG_RUNTIME_DIR is unset; harmless, but noisy.
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  mkdir -p /tmp/npr-xdg-runtime && chmod 700 /tmp/npr-xdg-runtime
fi
echo "setup: ok"
