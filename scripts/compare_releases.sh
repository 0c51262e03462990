#!/usr/bin/env bash
# Example 1 at n = 64 (64 steps) on Debian 12 (dolfinx 0.5.2), in the
# Debian 13 root (0.9.0) and in the sid root (0.11.0): the same discrete
# problem, so the probes of every step must agree to 1e-10 of their size.
# Needs the three builds (scripts/test.sh on each); prints the largest
# difference of each release from Debian 12's.
#   bash scripts/compare_releases.sh [N]
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-64}
run=(--config demos/square.json --set "mesh.n=$n" --set "time.steps=$n"
     --set output.xdmf=false --set output.nodal=none --quiet)
rm -rf out/release-12 out/release-13 out/release-sid
build/piezo-contact "${run[@]}" --output out/release-12
bash scripts/debian.sh trixie build/piezo-contact "${run[@]}" --output out/release-13
bash scripts/debian.sh sid build/piezo-contact "${run[@]}" --output out/release-sid
for other in 13 sid; do
  echo "Debian 12 vs $other:"
  /usr/bin/python3 tests/compare_summaries.py out/release-12/summary.json \
    "out/release-$other/summary.json" --tolerance 1e-10
done
