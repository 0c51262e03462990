#!/usr/bin/env bash
# Every demo of demos/, each at its shortest honest settings, the README's
# main command first: tests/demos/test_demos.py (pytest -m demo); fails when
# one fails (each demo exits non-zero when its engines disagree or its
# claims do not hold). Run by CI. Arguments go to pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
exec /usr/bin/python3 -m pytest tests/demos -m demo -v --durations=0 "$@"
