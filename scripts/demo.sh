#!/usr/bin/env bash
# Set up (install what is missing, build), then run the main demo: example 2
# of the paper, the piezoelectric contactor, on the executable and the
# reference engine, compared, and its pictures (out/contactor/*/figures/*.png).
# Arguments go to the demo, e.g.: bash scripts/demo.sh --set mesh.size=0.025
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
exec /usr/bin/python3 demos/demo_contactor.py "$@"
