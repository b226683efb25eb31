#!/usr/bin/env bash
# Cross-checks our T4 fundamental diagram with PedPy (the pedestrian-dynamics analysis library):
# installs PedPy from PyPI into a local venv (.pedpy-venv/, gitignored; needs the network the
# first time), writes the T4 periodic corridor's trajectories with
# `flockpath validate --tests t4 --pedpy-dir`, and lets PedPy compute the classic density and
# the mean speed along the corridor in the same measurement area (x 15…25 m, the middle of the
# periodic band x 10…30 m; the whole 2 m width; frames after the 10 s warm-up). Prints PedPy's
# figures beside ours.
#
# Not part of scripts/test.sh: it needs PyPI. Usage:
#   bash scripts/pedpy-check.sh [PLANNERS]     (default: boids; a comma-separated list or all)
set -euo pipefail
cd "$(dirname "$0")/.."
planners="${1:-boids}"
venv=.pedpy-venv
out=target/pedpy-check

if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import pedpy' 2>/dev/null; then
  echo "pedpy-check: installing PedPy into $venv (pip, PyPI)" >&2
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet --upgrade pip
  "$venv/bin/pip" install --quiet pedpy
fi

cargo build --release --quiet --bin flockpath
rm -rf "$out"
mkdir -p "$out"
./target/release/flockpath validate --tests t4 --planners "$planners" \
  --pedpy-dir "$out" --json "$out/report.json" > "$out/table.txt"

"$venv/bin/python" - "$out" <<'PY'
import json
import pathlib
import sys
import warnings

import numpy as np
import pedpy

warnings.filterwarnings("ignore")
out = pathlib.Path(sys.argv[1])
report = json.loads((out / "report.json").read_text())
# Our figures: the T4 curve per planner, columns as in `flockpath validate --csv-dir`.
ours = {}
for curve in report["curves"]:
    if curve["test"] == "t4-fundamental-diagram":
        for row in curve["rows"]:
            ours[(curve["planner"], row[0])] = (row[1], row[2])

area = pedpy.MeasurementArea([(15, 0), (25, 0), (25, 2), (15, 2)])
warm_up_frames = 100  # 10 s at 10 frames/s, as in the suite
print(f"PedPy {pedpy.__version__}: measurement area x 15..25 m, y 0..2 m, frames >= {warm_up_frames}")
print(f"{'planner':<9} {'rho':>4} | {'density ours':>12} {'PedPy':>7} | {'speed ours':>10} {'PedPy':>7} {'diff':>6}")
worst = 0.0
for path in sorted(out.glob("t4-fundamental-diagram-*-rho*.txt")):
    planner, rho = path.stem[len("t4-fundamental-diagram-"):].rsplit("-rho", 1)
    rho = float(rho)
    traj = pedpy.load_trajectory_from_txt(trajectory_file=path)
    density = pedpy.compute_classic_density(traj_data=traj, measurement_area=area)
    speed = pedpy.compute_individual_speed(
        traj_data=traj,
        frame_step=5,
        movement_direction=np.array([1.0, 0.0]),
        speed_calculation=pedpy.SpeedCalculation.BORDER_SINGLE_SIDED,
    )
    mean_speed = pedpy.compute_mean_speed_per_frame(
        traj_data=traj, individual_speed=speed, measurement_area=area
    )
    d = density[density.index >= warm_up_frames]["density"].mean()
    v = mean_speed[mean_speed.index >= warm_up_frames]["speed"].mean()
    d_ours, v_ours = ours.get((planner, rho), (float("nan"), float("nan")))
    worst = max(worst, abs(v - v_ours))
    print(f"{planner:<9} {rho:>4} | {d_ours:>12.3f} {d:>7.3f} | {v_ours:>10.3f} {v:>7.3f} {v - v_ours:>+6.3f}")
print(f"largest speed difference: {worst:.3f} m/s")
PY
