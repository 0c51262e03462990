#!/usr/bin/env bash
# A refactor keeps every number: every demo config of REV (as REV shipped
# it), at the small size the engines' agreement test uses, on this tree's
# executable and on REV's (REV checked out in out/tree-REV, built once in
# out/build-REV), every step record (all but its timing) compared bit for
# bit.
#   bash scripts/compare_builds.sh REV [KEY.PATH=VALUE ...]   # extra --set for both
# NEW_SET="KEY.PATH=VALUE ..." adds --set to this tree's runs only (a key REV
# does not know); TOLERANCE=1e-12 compares within that (relative to each
# field's largest value) instead of bit for bit.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=$(git rev-parse --short "$1"); shift
old=out/build-$rev
if [ ! -x "$old/piezo-contact" ] || [ ! -d "out/tree-$rev" ]; then
  rm -rf "out/tree-$rev"; git worktree prune
  git worktree add --detach "out/tree-$rev" "$rev" >/dev/null
  cmake -S "out/tree-$rev" -B "$old" -DCMAKE_BUILD_TYPE=Release -DPIEZO_PYTHON=OFF \
    -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
  cmake --build "$old" -j2 --target piezo-contact >/dev/null
fi
sizes=$(/usr/bin/python3 - <<'PY'
import ast, pathlib
tree = ast.parse(pathlib.Path("tests/engines/test_demo_agreement.py").read_text())
small = next(n.value for n in tree.body if isinstance(n, ast.Assign)
             and getattr(n.targets[0], "id", None) == "SMALL")
for name, sets in ast.literal_eval(small).items():
    print(name, *sets)
PY
)
status=0
while read -r config sets; do
  if [ ! -f "out/tree-$rev/demos/$config" ]; then # new since REV: nothing to compare
    printf '%-28s new since %s\n' "$config" "$rev"
    continue
  fi
  args=(--config "out/tree-$rev/demos/$config" --quiet --set output.xdmf=false --set output.nodal=none)
  for s in $sets "$@"; do args+=(--set "$s"); done
  for b in old new; do
    exe=$([ $b = old ] && echo "$old/piezo-contact" || echo build/piezo-contact)
    extra=()
    if [ $b = new ]; then for s in ${NEW_SET:-}; do extra+=(--set "$s"); done; fi
    rm -rf "out/compare-$b/$config"
    "$exe" "${args[@]}" "${extra[@]}" --output "out/compare-$b/$config"
  done
  printf '%-28s ' "$config"
  /usr/bin/python3 tests/compare_summaries.py "out/compare-old/$config/summary.json" \
    "out/compare-new/$config/summary.json" \
    $([ -n "${TOLERANCE:-}" ] && echo "--tolerance $TOLERANCE" || echo --identical) || status=1
done <<< "$sizes"
exit $status
