#!/usr/bin/env bash
# Set up (install what is missing, build), then reproduce a verification
# study (docs/verification.md):
#   bash scripts/verify.sh figure3 [--finest 256] [--solver reference]
#       the paper's Figure 3 on example 1 -> out/convergence/
#   bash scripts/verify.sh manufactured [--finest 128] [--solver cpp]
#       manufactured-solution rates in h and k -> out/manufactured/
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
  figure3) study=demos/convergence_study.py ;;
  manufactured) study=demos/manufactured_rates.py ;;
  *) echo "usage: bash scripts/verify.sh figure3|manufactured [options of the study]" >&2
     exit 2 ;;
esac
shift
bash scripts/setup.sh
exec /usr/bin/python3 "$study" "$@"
