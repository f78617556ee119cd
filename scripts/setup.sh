#!/usr/bin/env bash
# Idempotent set-up of a fresh machine for rapidgen: a virtual environment in .venv with
# rapidgen (editable) and its test dependencies. Sourced by scripts/test and scripts/demo.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="$ROOT/.venv"
PY="${PYTHON:-python3}"

if [ ! -x "$VENV/bin/python" ]; then
    echo "setup: creating $VENV" >&2
    "$PY" -m venv "$VENV"
fi
# Reinstall only when the project's dependency list changed since the last install.
STAMP="$VENV/.rapidgen-installed"
WANT="$(cat "$ROOT/pyproject.toml" "$ROOT/runtime/pyproject.toml" | sha256sum | cut -d' ' -f1)"
if [ ! -f "$STAMP" ] || [ "$(cat "$STAMP")" != "$WANT" ]; then
    echo "setup: installing rapidgen and test dependencies" >&2
    "$VENV/bin/python" -m pip install --quiet --upgrade pip >&2
    "$VENV/bin/python" -m pip install --quiet -e "$ROOT[test]" >&2
    # The asset runtime (runtime/): what a generated package's bridge runs on.
    "$VENV/bin/python" -m pip install --quiet -e "$ROOT/runtime" >&2
    echo "$WANT" > "$STAMP"
fi
# Foxglove's npm libraries (tests/node/package-lock.json), with which the tests read
# recordings and the Foxglove WebSocket server as Foxglove does: `npm ci` only when the lock
# changed since the last install (or node_modules is gone). Without npm the tests that need
# them fail and say so.
NODE_DIR="$ROOT/tests/node"
NODE_STAMP="$NODE_DIR/node_modules/.rapidgen-installed"
if command -v npm >/dev/null; then
    NODE_WANT="$(sha256sum "$NODE_DIR/package-lock.json" | cut -d' ' -f1)"
    if [ ! -f "$NODE_STAMP" ] || [ "$(cat "$NODE_STAMP")" != "$NODE_WANT" ]; then
        echo "setup: installing tests/node (npm ci)" >&2
        (cd "$NODE_DIR" && npm ci --ignore-scripts --no-audit --no-fund --silent >&2)
        echo "$NODE_WANT" > "$NODE_STAMP"
    fi
else
    echo "setup: npm not found: the tests that read with Foxglove's libraries (tests/node) will fail" >&2
fi
# Debian packages (scripts/apt-packages.txt), installed only when one is missing.
# RAPIDGEN_SKIP_APT=1 skips this (e.g. a machine without root, for the pure-Python tiers).
if [ -z "${RAPIDGEN_SKIP_APT:-}" ] && command -v dpkg-query >/dev/null; then
    mapfile -t PKGS < <(grep -v '^\s*#' "$ROOT/scripts/apt-packages.txt" | grep -v '^\s*$')
    MISSING=()
    for p in "${PKGS[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || MISSING+=("$p")
    done
    # cargo (tests/qos fetches cyclonedds.xsd from the cyclors crate; tests/rust builds the
    # generated crates): rustup's when there is one (on PATH or in $CARGO_HOME/bin), else
    # Debian's, with its clippy. Not in apt-packages.txt: the dpkg check by name would
    # install Debian's beside rustup's.
    if ! command -v cargo >/dev/null && [ ! -x "${CARGO_HOME:-$HOME/.cargo}/bin/cargo" ]; then
        MISSING+=(cargo rust-clippy)
    fi
    if [ "${#MISSING[@]}" -gt 0 ]; then
        echo "setup: installing Debian packages: ${MISSING[*]}" >&2
        SUDO=""
        [ "$(id -u)" -ne 0 ] && SUDO="sudo"
        export DEBIAN_FRONTEND=noninteractive
        $SUDO apt-get update -qq >&2 || true
        $SUDO apt-get install -y -qq --no-install-recommends "${MISSING[@]}" >&2
    fi
fi
# The Python side of DDS Security: Cyclone DDS with its security plugins under the venv's
# cyclonedds binding (the wheel has none); built once, after the Debian packages (cmake, g++).
if [ -z "${RAPIDGEN_SKIP_APT:-}" ]; then
    bash "$ROOT/scripts/cyclone_security.sh" "$VENV"
fi
export PATH="$VENV/bin:$PATH"
