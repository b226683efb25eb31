#!/usr/bin/env bash
# Checks the validation suite's verdicts against JuPedSim (the field's reference simulator):
# installs jupedsim 1.4.2 and PedPy from PyPI into a local venv (.jupedsim-venv/, gitignored;
# needs the network the first time), writes the suite's runs as set-ups
# (`flockpath validate --scenes-dir`: flockpath's own scene JSON plus the walkers' starts and
# speeds), runs each in JuPedSim's collision-free speed model and social force model
# (scripts/jupedsim_runs.py), measures the trajectories with flockpath's own measurement code
# (`flockpath validate --replay`) and prints the table test × model beside flockpath's baselines.
#
# Not part of scripts/test.sh: it needs PyPI. Usage:
#   bash scripts/jupedsim-check.sh [TESTS] [BASELINES]
#     TESTS      comma-separated test ids or prefixes (default all: every test's goals are
#                exits, which is what the translation needs)
#     BASELINES  flockpath planners to show beside JuPedSim (default
#                orca,social_force,collision_free_speed)
set -euo pipefail
cd "$(dirname "$0")/.."
tests="${1:-all}"
baselines="${2:-orca,social_force,collision_free_speed}"
venv=.jupedsim-venv
out=target/jupedsim-check
# The planner whose configuration sets up the scenes: every planner gets the same desired
# speeds and starts, so any will do.
setter=social_force

if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import jupedsim, pedpy' 2>/dev/null; then
  echo "jupedsim-check: installing jupedsim 1.4.2 and PedPy into $venv (pip, PyPI)" >&2
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet --upgrade pip
  "$venv/bin/pip" install --quiet "jupedsim==1.4.2" pedpy
fi

cargo build --release --quiet --bin flockpath
rm -rf "$out"
mkdir -p "$out"
flockpath=./target/release/flockpath
# One run gives the baselines' rows and the set-ups (the setter's runs; the others' are alike).
planners="$baselines"
case ",$baselines," in *",$setter,"*) ;; *) planners="$baselines,$setter" ;; esac
"$flockpath" validate --tests "$tests" --planners "$planners" --json "$out/flockpath.json" \
  --scenes-dir "$out/all-scenes" > "$out/flockpath.txt"
mkdir -p "$out/scenes"
mv "$out"/all-scenes/*-"$setter"*.json "$out/scenes/"
for model in cfsm sfm; do
  "$venv/bin/python" scripts/jupedsim_runs.py "$out/scenes" "$out/$model" "$model" "jupedsim-$model" "$setter"
  "$flockpath" validate --tests "$tests" --planners "$setter" --replay "$out/$model" --label "jupedsim-$model" \
    --json "$out/$model.json" > "$out/$model.txt"
done

"$venv/bin/python" - "$out" "$baselines" <<'PY'
import json
import pathlib
import sys

out = pathlib.Path(sys.argv[1])
shown = sys.argv[2].split(",")
rows = [r for r in json.loads((out / "flockpath.json").read_text())["rows"] if r["planner"] in shown]
for name in ["cfsm", "sfm"]:
    rows += json.loads((out / f"{name}.json").read_text())["rows"]
tests = list(dict.fromkeys(r["test"] for r in rows))
models = list(dict.fromkeys(r["planner"] for r in rows))
cell = {(r["test"], r["planner"]): r for r in rows}
print("| test | " + " | ".join(models) + " |")
print("|---" * (len(models) + 1) + "|")
for t in tests:
    cells = []
    for m in models:
        r = cell.get((t, m))
        if r is None:
            cells.append("")
            continue
        verdict = "**pass**" if r["pass"] else "fail"
        cells.append(f"{verdict}: {r['measured']}".replace("|", "\\|"))
    print(f"| `{t}` | " + " | ".join(cells) + " |")
for m in models:
    n = sum(1 for t in tests if cell.get((t, m), {}).get("pass"))
    print(f"{m}: {n} of {len(tests)} pass", file=sys.stderr)
PY
