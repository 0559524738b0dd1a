#!/usr/bin/env bash
# Set up a fresh Debian/Ubuntu machine for npr. Safe to run repeatedly.
#
#   ./setup.sh          what rendering needs: a Vulkan driver (Mesa's software
#                       driver, lavapipe, when none is installed) and cargo.
#   ./setup.sh --tests  that, plus what the test suite needs: Chromium (the
#                       studio's browser test and the WebGPU portability test),
#                       Node.js and the VS Code extension's npm packages, Xvfb
#                       and winit's X11 libraries (the `npr view` and embedding
#                       windows), ffmpeg (video
#                       output), Blender and python3-numpy (a real
#                       renderer's passes as a style's inputs), openjd-cli (the
#                       render-farm job template), the wasm32 target (the
#                       Bevy plugin's web build check, the npr-web package)
#                       and wasm-bindgen-cli at Cargo.lock's version
#                       (web/build.sh).
#
# Rendering an image needs none of the test tools, so the README's first
# command does not wait for them.
set -euo pipefail
cd "$(dirname "$0")"

want_tests=0
for arg in "$@"; do
  case "$arg" in
    --tests) want_tests=1 ;;
    -h|--help) sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "setup: unknown option '$arg' (expected --tests)" >&2; exit 2 ;;
  esac
done

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
apt_updated=0
# Installs Debian packages, running `apt-get update` at most once.
apt_install() {
  export DEBIAN_FRONTEND=noninteractive
  if [ "$apt_updated" -eq 0 ]; then
    $SUDO apt-get update -qq
    apt_updated=1
  fi
  $SUDO apt-get install -y -qq "$@" >/dev/null
}

# True when any Vulkan driver manifest is installed. (A `ls a/* b/* | grep`
# pipeline fails under pipefail when one folder is missing, which made every
# run reinstall Mesa.)
have_vulkan_icd() {
  local manifest
  for manifest in /usr/share/vulkan/icd.d/*.json /etc/vulkan/icd.d/*.json; do
    [ -e "$manifest" ] && return 0
  done
  return 1
}

if ! command -v cargo >/dev/null 2>&1; then
  echo "setup: cargo not found; install Rust from your distribution or rustup" >&2
  exit 1
fi

# rust-toolchain.toml pins the Rust release (Bevy 0.20, which bevy_mod_npr
# builds on, needs 1.97.1); rustup installs it once, with clippy and rustfmt.
if command -v rustup >/dev/null 2>&1; then
  toolchain=$(sed -n 's/^channel = "\(.*\)"/\1/p' rust-toolchain.toml)
  rustup toolchain install --no-self-update --profile minimal \
    --component clippy --component rustfmt "$toolchain" >/dev/null
fi

if ! have_vulkan_icd; then
  echo "setup: no Vulkan driver found; installing Mesa's software driver (apt: mesa-vulkan-drivers)"
  apt_install mesa-vulkan-drivers libvulkan1
fi

# The Vulkan loader warns when XDG_RUNTIME_DIR is unset; harmless, but noisy.
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  mkdir -p /tmp/npr-xdg-runtime && chmod 700 /tmp/npr-xdg-runtime
fi

if [ "$want_tests" -eq 1 ]; then
  missing=()
  # tests/general/studio_browser.rs and webgpu_portability.rs drive Debian's
  # Chromium headless over the DevTools protocol; no browser is downloaded.
  [ -x /usr/bin/chromium ] || missing+=(chromium)
  # tests/general/vscode_extension.rs runs the extension's grammar with
  # vscode-textmate and drives `npr lsp` with vscode-jsonrpc.
  command -v npm >/dev/null 2>&1 || missing+=(nodejs npm)
  # `npr view` and examples/embed.rs open real windows on an X server.
  command -v Xvfb >/dev/null 2>&1 || missing+=(xvfb)
  command -v xdpyinfo >/dev/null 2>&1 || missing+=(x11-utils)
  # winit loads these X11 libraries at run time (dlopen), so nothing fails
  # to link without them; the window does not open.
  # `grep -q` would stop reading at the first match and make ldconfig die of
  # SIGPIPE, which pipefail turns into "missing" (an apt run every time).
  local_lib() { ldconfig -p | grep -F "$1" >/dev/null; }
  local_lib libxkbcommon-x11.so.0 || missing+=(libxkbcommon-x11-0)
  local_lib libX11-xcb.so.1 || missing+=(libx11-xcb1)
  local_lib libXcursor.so.1 || missing+=(libxcursor1)
  local_lib libXi.so.6 || missing+=(libxi6)
  local_lib libXrandr.so.2 || missing+=(libxrandr2)
  # Video and GIF output pipe frames to ffmpeg.
  command -v ffmpeg >/dev/null 2>&1 || missing+=(ffmpeg)
  # The host-inputs tests render a real renderer's passes with Blender
  # (Cycles, headless); its Python needs Debian's numpy on the system PATH.
  [ -x /usr/bin/blender ] || missing+=(blender)
  PATH=/usr/bin:/bin python3 -c 'import numpy' >/dev/null 2>&1 || missing+=(python3-numpy)
  if [ "${#missing[@]}" -gt 0 ]; then
    echo "setup: installing the test suite's tools (apt: ${missing[*]})"
    apt_install "${missing[@]}"
  fi
  # CI checks that bevy_mod_npr without default features builds for the web.
  if command -v rustup >/dev/null 2>&1; then
    rustup target add --toolchain "$toolchain" wasm32-unknown-unknown >/dev/null
  fi
  # web/build.sh binds npr-web with wasm-bindgen, whose command-line tool
  # must be exactly the version of the wasm-bindgen crate in Cargo.lock.
  bindgen_want=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
  bindgen_have=$(wasm-bindgen --version 2>/dev/null | awk '{ print $2 }' || true)
  if [ "$bindgen_have" != "$bindgen_want" ]; then
    echo "setup: installing wasm-bindgen-cli $bindgen_want (cargo install; found: ${bindgen_have:-none})"
    # --locked first (the tool's own lock file); a registry that lacks one of
    # the versions it pins (seen: webpki-roots) gets a fresh resolution of
    # its dependencies, the tool's version still exact.
    if ! cargo install --locked --quiet wasm-bindgen-cli --version "$bindgen_want"; then
      echo "setup: wasm-bindgen-cli $bindgen_want with its lock file failed; installing it with its dependencies resolved afresh"
      cargo install --quiet wasm-bindgen-cli --version "$bindgen_want"
    fi
  fi
  if [ ! -d editors/vscode/node_modules/vscode-textmate ]; then
    echo "setup: npm ci in editors/vscode (pinned by package-lock.json)"
    (cd editors/vscode && npm ci --no-audit --no-fund --loglevel=error)
  fi
  # The render-farm job template (farm/openjd/) is run by Open Job
  # Description's own runner, from PyPI.
  if ! command -v openjd >/dev/null 2>&1; then
    echo "setup: installing openjd-cli (pip) for the job template's test"
    python3 -m pip install --quiet --disable-pip-version-check --root-user-action=ignore openjd-cli
  fi
fi
echo "setup: ok"
