#!/usr/bin/env bash
# The Python side of DDS Security: Cyclone DDS 11.0.1 built with its security plugins, and
# the `cyclonedds` binding of VENV rebuilt against it (the PyPI wheel's libddsc has no DDS
# Security: a <Security> section is an unknown element to it). Run by scripts/setup.sh;
# about 40 s of a 2-core machine, once (a stamp skips it after).
#
#   scripts/cyclone_security.sh VENV
#
# The source is Cyclone DDS 11.0.1 as the cyclors crate vendors it, from crates.io (a
# registry every machine here reaches; pinned by its checksum). One patch goes with it
# (scripts/cyclone-fastdds-dh.patch, docs/security.md "The Python side"): Fast DDS 2.9 puts
# a DH public key on the wire as raw big-endian bytes where Cyclone writes and expects a DER
# INTEGER, so without it no handshake that Fast DDS starts ever completes.
# Everything goes to VENV/cyclonedds-security (lib/ with libddsc and the three plugins,
# found through RUNPATH: no LD_LIBRARY_PATH needed).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="$(cd "$1" && pwd)"
PREFIX="$VENV/cyclonedds-security"
CRATE_URL="https://static.crates.io/crates/cyclors/cyclors-0.4.0.crate"
CRATE_SHA256="6beb8dc0574f6e2184a2a67c6833ff7ab5b64a95d2459db9b009797b0bb7374e"
BINDING="cyclonedds==11.0.1"
PATCH="$ROOT/scripts/cyclone-fastdds-dh.patch"

STAMP="$PREFIX/.installed"
WANT="$(printf '%s %s %s' "$CRATE_SHA256" "$BINDING" "$(sha256sum "$PATCH" "$0" | cut -d' ' -f1 | tr '\n' ' ')")"
LIBRARY_PY="$("$VENV/bin/python" -c 'import importlib.util as u; s = u.find_spec("cyclonedds"); print(s.submodule_search_locations[0] if s else "")')/__library__.py"
# done when the stamp matches and the binding is still the one built here (pip may have put the wheel back)
if [ -f "$STAMP" ] && [ "$(cat "$STAMP")" = "$WANT" ] && grep -qF "$PREFIX/lib/libddsc.so" "$LIBRARY_PY" 2>/dev/null; then
    exit 0
fi
echo "setup: building Cyclone DDS 11.0.1 with DDS Security for the Python tools (once)" >&2
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
curl -sSfL --retry 3 -o "$WORK/cyclors.crate" "$CRATE_URL"
echo "$CRATE_SHA256  $WORK/cyclors.crate" | sha256sum -c --quiet -
tar -xzf "$WORK/cyclors.crate" -C "$WORK" cyclors-0.4.0/cyclonedds
SRC="$WORK/cyclors-0.4.0/cyclonedds"
patch -s -p1 -d "$SRC" < "$PATCH"
rm -rf "$PREFIX"
cmake -S "$SRC" -B "$WORK/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$PREFIX" \
    -DENABLE_SECURITY=ON -DENABLE_SSL=ON -DBUILD_EXAMPLES=OFF \
    -DBUILD_TESTING=OFF -DBUILD_DDSPERF=OFF -DENABLE_SHM=OFF -DENABLE_ICEORYX=OFF >/dev/null
cmake --build "$WORK/build" --parallel "$(nproc)" >/dev/null
cmake --install "$WORK/build" >/dev/null
# The binding from its source distribution, linked to that libddsc (RUNPATH: the plugins are
# dlopen'ed by libddsc, which finds them through its own RUNPATH).
CYCLONEDDS_HOME="$PREFIX" LDFLAGS="-Wl,-rpath,$PREFIX/lib" \
    "$VENV/bin/python" -m pip install --quiet --no-deps --force-reinstall --no-cache-dir --no-binary cyclonedds "$BINDING" >&2
# The binding looks for libddsc on the library path before its own install path (cyclonedds/
# internal.py's loaders), and Debian's cyclonedds-tools brings a libddsc 0.10 there: mark the
# build as the binding's own so that its recorded path is tried first.
LIBRARY_PY="$("$VENV/bin/python" -c 'import importlib.util as u; print(u.find_spec("cyclonedds").submodule_search_locations[0])')/__library__.py"
sed -i 's/^in_wheel = False$/in_wheel = True/' "$LIBRARY_PY"
grep -q "^in_wheel = True" "$LIBRARY_PY" && grep -q "$PREFIX/lib/libddsc.so" "$LIBRARY_PY"
echo "$WANT" > "$STAMP"
