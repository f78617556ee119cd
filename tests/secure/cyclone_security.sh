#!/usr/bin/env bash
# Cyclone DDS 11.0.1 with DDS Security, and a Python environment whose `cyclonedds` binding
# is built against it: what the Python bridge and tools need to run secured (the PyPI wheel
# is built without DDS Security: its libddsc refuses a <Security> section as an unknown
# element). About 7 minutes on a 2-core machine. docs/security.md, "The Python side".
#
#   tests/secure/cyclone_security.sh PREFIX [CYCLONE_SOURCE]
#   RAPIDGEN_CYCLONE_SECURITY=PREFIX pytest tests/secure/test_python_secured.py
#
# PREFIX gets lib/ (libddsc.so.11 and libdds_security_{auth,ac,crypto}.so) and venv/ (the
# binding, rapidgen and rapid_runtime, editable). Run the Python side with
#   LD_LIBRARY_PATH=PREFIX/lib CYCLONEDDS_HOME=PREFIX \
#   CYCLONEDDS_URI=file://<transport>.xml,file://KEYSTORE/enclaves/NAME/cyclonedds-security.xml
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PREFIX=$(mkdir -p "$1" && cd "$1" && pwd)
SRC=${2:-}
if [ -z "$SRC" ]; then
    SRC=$PREFIX/src
    [ -d "$SRC" ] || git clone --quiet --depth 1 --branch 11.0.1 https://github.com/eclipse-cyclonedds/cyclonedds "$SRC"
fi
cmake -S "$SRC" -B "$PREFIX/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_INSTALL_PREFIX="$PREFIX" \
    -DENABLE_SECURITY=ON -DENABLE_SSL=ON -DBUILD_EXAMPLES=OFF -DBUILD_TESTING=OFF -DENABLE_SHM=OFF \
    -DENABLE_ICEORYX=OFF -DBUILD_DDSPERF=OFF >/dev/null
cmake --build "$PREFIX/build" -j"$(nproc)" >/dev/null
cmake --install "$PREFIX/build" >/dev/null
python3 -m venv "$PREFIX/venv"
"$PREFIX/venv/bin/pip" install --quiet --upgrade pip setuptools wheel
CYCLONEDDS_HOME=$PREFIX "$PREFIX/venv/bin/pip" install --quiet --no-binary cyclonedds cyclonedds==11.0.1
"$PREFIX/venv/bin/pip" install --quiet -e "$ROOT" -e "$ROOT/runtime"
echo "RAPIDGEN_CYCLONE_SECURITY=$PREFIX"
