"""Runs the validation suite's runs in JuPedSim (scripts/jupedsim-check.sh).

Reads each run's set-up as `flockpath validate --scenes-dir` writes it (the scene JSON in px with
its px_per_metre, the walkers' starts in metres, each group's desired speed, the periodic band,
the run's length and frame interval), builds the same scene in JuPedSim and writes the
trajectories in the suite's text format for `flockpath validate --replay`, so flockpath's own
measurement code judges them.

Translation (one place): the walkable area is the world's rectangle minus every obstacle; each
exit goal (a disc) is an exit stage, the disc cut to the walkable area; each group's walkers get
a journey to their goal's exit, their body radius less half a millimetre (BODY_SLACK_M) and
their desired speed. Coordinates stay as in flockpath (x right, y down): both models are
mirror-symmetric, so the mirror changes nothing.

The body slack: JuPedSim 1.4.2 refuses to add a collision-free-speed walker whose centre is
within r1 + r2 of another's, touching included (`contact distance >= distance` is a "model
constraint violation"), while flockpath lets bodies touch. At T16's 2.5 persons/m with 0.2 m
radii the lattice's walkers are exactly 0.4 m apart, one body length: whether a pair is refused
is decided by the last bit of a float sum (walker 29 was the first), and no nudge helps in a ring
that is full. Bodies 1 mm narrower in diameter than flockpath's fit; 1 mm is 0.25% of a body.

Not JuPedSim's: the periodic corridor. JuPedSim has no periodic boundary, so a walker whose
centre leaves the band is removed and added back at the other end (same y, a new JuPedSim id,
the same id in the output; when that place is taken it walks on and tries again at the next
iteration); nobody sees neighbours across the seam, which is why the suite
measures in the band's middle; the walkers start on a lattice over the band (JuPedSim refuses
the overlapping bodies flockpath's random spawn allows at 5–6 persons/m²). A walker removed at an exit is written, from the next frame on,
at the exit's centre (on the far side of the exit line), so the crossing is found between its
last place and there (to within one frame).
"""

import json
import math
import pathlib
import sys

import jupedsim as jps
import shapely
from shapely.geometry import Point, Polygon, box

DT = 0.01
# How much narrower (m, in diameter) JuPedSim's bodies are than flockpath's, so that bodies that
# touch in flockpath are apart in JuPedSim (see the module's note).
BODY_SLACK_M = 1e-3


def walkable_area(scene, ppm):
    """The world's rectangle minus the obstacles, in metres."""
    area = box(0.0, 0.0, scene["width"] / ppm, scene["height"] / ppm)
    holes = []
    for o in scene.get("obstacles", []):
        shape = o.get("shape")
        if shape == "rect":
            (x0, y0), (x1, y1) = o["min"], o["max"]
            holes.append(box(x0 / ppm, y0 / ppm, x1 / ppm, y1 / ppm))
        elif shape == "polygon":
            holes.append(Polygon([(x / ppm, y / ppm) for x, y in o["points"]]))
        elif shape == "circle":
            (cx, cy), r = o["centre"], o["radius"]
            holes.append(Point(cx / ppm, cy / ppm).buffer(r / ppm, 32))
        else:
            raise SystemExit(f"obstacle shape {shape!r} has no translation")
    if holes:
        area = area.difference(shapely.unary_union(holes))
    if area.geom_type == "MultiPolygon":
        area = max(area.geoms, key=lambda g: g.area)
    return area


def exit_polygon(goal, area, ppm):
    """An exit goal's disc cut to the walkable area (JuPedSim wants exits inside it)."""
    (gx, gy), r = goal["position"], goal["radius"]
    disc = Point(gx / ppm, gy / ppm).buffer(r / ppm, 32).intersection(area)
    if disc.geom_type == "MultiPolygon":
        disc = max(disc.geoms, key=lambda g: g.area)
    return disc


def model_and_agent(model):
    """The JuPedSim model and a function making an agent's parameters."""
    if model == "cfsm":
        def params(pos, journey, stage, speed, radius):
            return jps.CollisionFreeSpeedModelAgentParameters(
                position=pos, journey_id=journey, stage_id=stage, desired_speed=speed, radius=radius
            )
        return jps.CollisionFreeSpeedModel(), params
    if model == "sfm":
        def params(pos, journey, stage, speed, radius):
            return jps.SocialForceModelAgentParameters(
                position=pos, orientation=(1.0, 0.0), journey_id=journey, stage_id=stage,
                desired_speed=speed, radius=radius,
            )
        return jps.SocialForceModel(), params
    raise SystemExit(f"unknown model {model!r}")


def lattice(starts, band, area, groups, group_of, ppm):
    """The periodic corridor's walkers on a lattice over the band, in the starts' order:
    flockpath spawns them at random and lets bodies touch, JuPedSim refuses overlapping bodies,
    so at 5–6 persons/m² no random start is free. Hexagonal rows across the corridor's width,
    the walkers spread evenly along each row."""
    # JuPedSim's diameter plus the slack: flockpath's diameter.
    diameter = 2 * max(g["agent_radius"] for g in groups) / ppm
    _, y0, _, y1 = area.bounds
    width = y1 - y0
    # Hexagonal rows: neighbouring rows offset by half a step may be 0.87 diameters apart.
    rows = max(1, int((width - diameter) / (0.87 * diameter)) + 1)
    n = len(starts)
    per_row = math.ceil(n / rows)
    length = band[1] - band[0]
    out = []
    for i in range(n):
        r, c = i % rows, i // rows
        x = band[0] + (c + 0.5 * (r % 2)) * length / per_row
        y = (y0 + y1) / 2 if rows == 1 else y0 + diameter / 2 + r * (width - diameter) / (rows - 1)
        out.append((min(x, band[1] - 1e-3), y))
    return out


def run(setup, model):
    """Runs one set-up with `model`; returns the trajectory text."""
    scene = setup["scene"]
    ppm = scene.get("px_per_metre", 20.0)
    area = walkable_area(scene, ppm)
    jps_model, agent = model_and_agent(model)
    sim = jps.Simulation(model=jps_model, geometry=area, dt=DT)
    goals = scene["goals"]
    routes = []
    for goal in goals:
        if goal.get("on_arrival") != "exit":
            raise SystemExit("a goal that is not an exit has no translation yet")
        stage = sim.add_exit_stage(exit_polygon(goal, area, ppm))
        journey = sim.add_journey(jps.JourneyDescription([stage]))
        centre = (goal["position"][0] / ppm, goal["position"][1] / ppm)
        routes.append((journey, stage, centre))
    groups = scene["groups"]
    band = setup.get("periodic_band_m")
    ours = {}  # JuPedSim id -> our walker index
    group_of = setup["group_of"]

    def add(index, pos):
        g = groups[group_of[index]]
        journey, stage, _ = routes[g["goal"]]
        speed = setup["desired_speed_m_s"][group_of[index]]
        radius = g["agent_radius"] / ppm - BODY_SLACK_M / 2
        ours[sim.add_agent(agent(tuple(pos), journey, stage, speed, radius))] = index

    starts = setup["starts_m"]
    if band:
        starts = lattice(starts, band, area, groups, group_of, ppm)
    for index, start in enumerate(starts):
        # JuPedSim refuses a walker overlapping another where flockpath's spawn lets bodies
        # touch: nudge it along x by up to ±0.25 m, the nearest free place first.
        for nudge in [0.0] + [s * k * 0.025 for k in range(1, 11) for s in (1, -1)]:
            try:
                add(index, (start[0] + nudge, start[1]))
                break
            except RuntimeError:
                continue
        else:
            raise SystemExit(f"walker {index + 1} finds no free place near its start {start}")
    per_frame = max(1, round(setup["frame_s"] / DT))
    frames = int(setup["seconds"] / setup["frame_s"] + 1e-6)
    n = len(setup["starts_m"])
    last = [None] * n
    gone = [False] * n
    lines = [
        f"# JuPedSim {jps.__version__} {model}: {setup['scene']['name']}",
        f"# framerate: {1.0 / setup['frame_s']:.4f}",
        "# id frame x/m y/m z/m",
    ]
    for k in range(frames + 1):
        seen = set()
        for a in sim.agents():
            i = ours.get(a.id)
            if i is not None:  # not a walker that wrapped, waiting for its removal
                last[i] = a.position
                seen.add(i)
        for i in range(n):
            if i not in seen and not gone[i] and last[i] is not None and k > 0:
                gone[i] = True
            if gone[i]:
                _, _, centre = routes[groups[group_of[i]]["goal"]]
                x, y = centre
            else:
                x, y = last[i]
            lines.append(f"{i + 1} {k} {x:.4f} {y:.4f} 0")
        if k == frames or sim.agent_count() == 0:
            break
        stopped = None
        for _ in range(per_frame):
            try:
                sim.iterate()
            except RuntimeError as e:  # e.g. SFM pushing a walker out of a 0.5 m corridor
                stopped = f"# stopped by JuPedSim at {sim.elapsed_time():.2f} s: {e}"
                break
            if band:
                wrap = []
                for a in sim.agents():
                    if a.id not in ours:
                        continue
                    x, y = a.position
                    if x >= band[1]:
                        wrap.append((a.id, (x - (band[1] - band[0]), y)))
                    elif x < band[0]:
                        wrap.append((a.id, (x + (band[1] - band[0]), y)))
                for jid, pos in wrap:
                    # JuPedSim refuses a walker overlapping another: it walks on past the band
                    # (there is room) and tries again at the next iteration.
                    i = ours.pop(jid)
                    try:
                        add(i, pos)
                    except RuntimeError:
                        ours[jid] = i
                        continue
                    sim.mark_agent_for_removal(jid)
        if stopped:
            print(f"jupedsim-check: {setup['scene']['name']} {stopped[2:]}", file=sys.stderr)
            lines.insert(2, stopped)
            break
    return "\n".join(lines) + "\n"


def main():
    scenes, out, model, label, scene_label = sys.argv[1:6]
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    for path in sorted(pathlib.Path(scenes).glob("*.json")):
        setup = json.loads(path.read_text())
        name = path.stem.replace(f"-{scene_label}", f"-{label}", 1)
        print(f"jupedsim-check: {name}", file=sys.stderr, flush=True)
        (out / f"{name}.txt").write_text(run(setup, model))


if __name__ == "__main__":
    main()
