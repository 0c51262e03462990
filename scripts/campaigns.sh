#!/usr/bin/env bash
# The campaigns the default suite leaves out (pytest -m slow): editing the
# forms and rebuilding a copy of the tree, 100 kills at random instants,
# 260 more fuzz cases. Set up as scripts/test.sh does.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
exec /usr/bin/python3 -m pytest tests -m slow "$@"
