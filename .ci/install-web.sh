#!/usr/bin/env bash
# Installs what the WebAssembly and web-page checks need on a fresh machine (idempotent):
# the wasm32 Rust target, Debian's binaryen (wasm-opt) and chromium, and the page's npm
# packages (playwright-core, pinned by examples/web/package-lock.json; no browser download).
set -euo pipefail
cd "$(dirname "$0")/.."

if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    rustup target add wasm32-unknown-unknown
fi

missing=()
command -v wasm-opt >/dev/null 2>&1 || missing+=(binaryen)
[ -x /usr/bin/chromium ] || missing+=(chromium)
if [ ${#missing[@]} -gt 0 ]; then
    SUDO=""
    [ "$(id -u)" -eq 0 ] || SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

if [ ! -d examples/web/node_modules/playwright-core ]; then
    (cd examples/web && npm ci --no-audit --no-fund)
fi
