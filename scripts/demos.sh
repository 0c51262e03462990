#!/usr/bin/env bash
# Every demo of demos/, each at its shortest honest settings, after the
# README's main command; fails when one fails (each demo exits non-zero
# when its engines disagree or its claims do not hold). Run by CI.
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=${DEMOS_OUTPUT:-out/ci-demos}
demo() {
  local start=$SECONDS
  echo "demos: $*"
  "$@" >"$out/log.txt" 2>&1 || { cat "$out/log.txt"; echo "demos: FAILED: $*"; exit 1; }
  grep -h "agree\|DISAGREE\|CONTACT\|rate" "$out/log.txt" | tail -4 || true
  echo "demos: passed in $((SECONDS - start)) s"
}
mkdir -p "$out"
demo bash scripts/demo.sh --output "$out/contactor"
demo /usr/bin/python3 demos/demo_square.py --output "$out/square" --set mesh.n=16 --set time.steps=16
demo /usr/bin/python3 demos/demo_unimorph.py --output "$out/unimorph"
demo /usr/bin/python3 demos/demo_sensor.py --output "$out/sensor"
demo /usr/bin/python3 demos/demo_python_api.py --output "$out/api"
demo /usr/bin/python3 demos/manufactured_rates.py --finest 16 --output "$out/manufactured"
demo /usr/bin/python3 demos/convergence_study.py --finest 16 --output "$out/figure3"
