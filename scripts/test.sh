#!/usr/bin/env bash
# Set up (install what is missing, build), then run the tests: the C++
# unit and run tests (ctest) and the cross-checks (pytest), all but the
# campaigns and the demos (scripts/campaigns.sh, scripts/demos.sh;
# `-m "not demo"` runs the campaigns too, `-m "slow or not slow"` all).
# Arguments go to pytest, e.g.: bash scripts/test.sh -k agreement
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# mpirun refuses to start as root unless told it may
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
(cd build && ctest --output-on-failure)
exec /usr/bin/python3 -m pytest tests "$@"
