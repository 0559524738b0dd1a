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

# The studio's browser test (tests/studio_browser.rs) drives Debian's
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

# The Vulkan loader warns when XDG_RUNTIME_DIR is unset; harmless, but noisy.
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  mkdir -p /tmp/npr-xdg-runtime && chmod 700 /tmp/npr-xdg-runtime
fi
echo "setup: ok"
