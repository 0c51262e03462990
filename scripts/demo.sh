#!/usr/bin/env bash
# Set up (install what is missing, build), then run the main demo: example 1
# of the paper with the C++ solver and its Python twin, compared.
# Arguments go to the demo, e.g.: bash scripts/demo.sh --set mesh.n=64
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
exec /usr/bin/python3 demos/demo_square.py "$@"
