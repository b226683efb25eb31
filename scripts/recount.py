#!/usr/bin/env python3
"""Recounts what a run's picture shows from the positions alone (not from the metrics code)
and sets it beside `flockpath run --metrics`: per preset, agents whose centre is inside their
goal (where the goal is at the last step), the metrics' arrived and waiting counts, and the
overlapping pairs among agents at rest and among all agents at the last step.

    python3 scripts/recount.py [--bin target/release/flockpath] [--steps 3600] [PRESET ...]

Independent of the Rust metrics: it reads the CLI's path CSV and the scene JSON and does its
own geometry (goal motion included), so a disagreement points at one side or the other.
"""
import argparse, csv, json, math, os, subprocess, sys, tempfile

AT_REST = 0.05  # px/step


def goal_at(goal, step):
    x, y = goal["position"]
    m = goal.get("motion")
    if not m:
        return x, y
    if m["kind"] == "circle":
        cx, cy = m["center"]
        phase0 = math.atan2(y - cy, x - cx) if (x, y) != (cx, cy) else 0.0
        turns = (step / m["period_steps"]) % 1.0
        a = phase0 + turns * 2 * math.pi
        return cx + math.cos(a) * m["radius"], cy + math.sin(a) * m["radius"]
    left = m["speed"] * step
    pts = m["points"]
    at = pts[0]
    for nxt in pts[1:]:
        length = math.dist(at, nxt)
        if left <= length:
            t = left / length if length > 0 else 0
            return at[0] + (nxt[0] - at[0]) * t, at[1] + (nxt[1] - at[1]) * t
        left -= length
        at = nxt
    return tuple(at)


def recount(binary, preset, steps):
    scene = json.loads(subprocess.check_output([binary, "preset", preset]))
    with tempfile.TemporaryDirectory() as d:
        paths, metrics = os.path.join(d, "p.csv"), os.path.join(d, "m.json")
        subprocess.check_call([binary, "run", "--scene", "-", "--steps", str(steps), "--paths", paths,
                               "--metrics", metrics], input=None, stdin=open(os.devnull) if False else None,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) if False else None
        p = subprocess.run([binary, "run", "--scene", "-", "--steps", str(steps), "--paths", paths,
                            "--metrics", metrics], input=json.dumps(scene).encode(),
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        if p.returncode:
            raise SystemExit(p.stderr.decode())
        last = {}
        with open(paths) as f:
            for row in csv.DictReader(f):
                if int(row["step"]) == steps:
                    last[int(row["agent"])] = row
        m = json.load(open(metrics))
    radius, group_goal = [], []
    for g in scene["groups"]:
        radius += [g.get("agent_radius", 4.0)] * g["count"]
        group_goal += [g.get("goal")] * g["count"]
    n = len(radius)
    pos = [(float(last[i]["x"]), float(last[i]["y"])) for i in range(n)]
    speed = [math.hypot(float(last[i]["vx"]), float(last[i]["vy"])) for i in range(n)]
    inside = 0
    for i in range(n):
        k = group_goal[i]
        if k is None:
            continue
        goal = scene["goals"][k]
        if math.dist(pos[i], goal_at(goal, steps)) <= goal.get("radius", 20.0):
            inside += 1
    # Agents inside an exit have left the scene: they meet nobody.
    gone = set()
    for i in range(n):
        k = group_goal[i]
        if k is not None and scene["goals"][k].get("on_arrival") == "exit" and \
                math.dist(pos[i], goal_at(scene["goals"][k], steps)) <= scene["goals"][k].get("radius", 20.0):
            gone.add(i)
    rest_pairs = all_pairs = 0
    cell = 2 * max(radius) if radius else 1
    buckets = {}
    for i, (x, y) in enumerate(pos):
        if i in gone:
            continue
        buckets.setdefault((int(x // cell), int(y // cell)), []).append(i)
    for (cx, cy), ids in buckets.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for j in buckets.get((cx + dx, cy + dy), []):
                    for i in ids:
                        if i < j and math.dist(pos[i], pos[j]) < radius[i] + radius[j]:
                            all_pairs += 1
                            rest_pairs += speed[i] < AT_REST and speed[j] < AT_REST
    return {
        "preset": preset, "agents": n, "inside": inside,
        "arrived": round(m["arrived_share"] * n), "waiting": m.get("waiting_agents", "-"),
        "overlap_rest": rest_pairs, "overlap_all": all_pairs,
        "collisions_last": m["collisions_last_step"],
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default="target/release/flockpath")
    ap.add_argument("--steps", type=int, default=3600)
    ap.add_argument("presets", nargs="*")
    a = ap.parse_args()
    presets = a.presets or [l.split()[0] for l in subprocess.check_output([a.bin, "presets"]).decode().splitlines() if l.strip()]
    print("preset | agents | inside goal | arrived (metrics) | waiting (metrics) | overlapping pairs at rest | all overlapping pairs")
    bad = 0
    for name in presets:
        r = recount(a.bin, name, a.steps)
        print(f"{r['preset']} | {r['agents']} | {r['inside']} | {r['arrived']} | {r['waiting']} | {r['overlap_rest']} | {r['overlap_all']}")
        bad += r["inside"] != r["arrived"] or r["overlap_all"] != r["collisions_last"]
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
