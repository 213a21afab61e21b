#!/usr/bin/env bash
# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
# Run a command inside the workspace environment (venv + ROS wheels + colcon install),
# without anyone having to source anything by hand: tools/env.sh CMD [ARGS...]
set -eo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
export VIRTUAL_ENV="$ROOT/.venv"
export PATH="$VIRTUAL_ENV/bin:$PATH"
export AMENT_PREFIX_PATH="$VIRTUAL_ENV${AMENT_PREFIX_PATH:+:$AMENT_PREFIX_PATH}"
export COLCON_TRACE="${COLCON_TRACE:-}"
export AMENT_TRACE_SETUP_FILES="${AMENT_TRACE_SETUP_FILES:-}"
export AMENT_PYTHON_EXECUTABLE="$VIRTUAL_ENV/bin/python"
export COLCON_PYTHON_EXECUTABLE="$VIRTUAL_ENV/bin/python"
# shellcheck disable=SC1091
set +u
source "$ROOT/install/local_setup.bash"
# The ROS wheels' bootstrap (a .pth file) re-executes every Python process once with these
# library paths; set them here once, so no process (the CLI, each node) starts twice.
if [ -z "${_ROS_WHEELS_BOOTSTRAP_COMPLETE:-}" ]; then
    ros_libs=$(printf '%s:' "$VIRTUAL_ENV"/lib/python3*/site-packages/ros_*.libs)
    export LD_LIBRARY_PATH="$VIRTUAL_ENV/lib:${ros_libs}${LD_LIBRARY_PATH:-}"
    export _ROS_WHEELS_BOOTSTRAP_COMPLETE=1
fi
export ROS_AUTOMATIC_DISCOVERY_RANGE="${ROS_AUTOMATIC_DISCOVERY_RANGE:-LOCALHOST}"
export PYTHONUNBUFFERED=1
# The dense K&C matrices are small (~100-300): BLAS threads only contend (20x slower on 2 busy cores)
export OPENBLAS_NUM_THREADS="${OPENBLAS_NUM_THREADS:-1}" OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}"
exec "$@"
