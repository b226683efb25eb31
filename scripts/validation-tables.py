#!/usr/bin/env python3
"""Render docs/validation.md's measured tables from `flockpath validate --json`.

    ./target/release/flockpath validate --json report.json
    python3 scripts/validation-tables.py report.json docs/validation.md          # rewrite in place
    python3 scripts/validation-tables.py report.json docs/validation.md --check  # exit 1 if stale

The tables live in the Markdown between marker comments, so prose round them stays hand-written
and the figures are only ever the report's:

    <!-- validation-tables:begin NAME -->
    ...
    <!-- validation-tables:end NAME -->

NAME is `main` (test × planner, pass/fail and the measurement in words, and a row of pass counts),
`t4-speeds` or `t16-speeds` (the fundamental diagrams' speeds with the measured density in
brackets, and the reference at the nominal density). A block whose marker is absent is skipped,
so a fixture may hold only some. Standard library only: it runs wherever the CLI does.
"""

import json
import math
import sys

BEGIN = "<!-- validation-tables:begin {} -->"
END = "<!-- validation-tables:end {} -->"


def weidmann(rho):
    """Weidmann (1993), as docs/validation.md states it; 0 at and above the jam density 5.4."""
    if rho >= 5.4:
        return 0.0
    return 1.34 * (1.0 - math.exp(-1.913 * (1.0 / rho - 1.0 / 5.4)))


def seyfried(rho):
    """Seyfried et al. (2005): v = (1/ρ − 0.36)/1.06, within 0…1.34 m/s."""
    return min(1.34, max(0.0, (1.0 / rho - 0.36) / 1.06))


def cell(text):
    """A Markdown table cell: a literal | escaped."""
    return text.replace("|", "\\|")


def ordered(items):
    """Unique values in first-seen order (the report's own order: table order, PlannerKind::ALL)."""
    seen = []
    for item in items:
        if item not in seen:
            seen.append(item)
    return seen


def main_table(report):
    rows = report["rows"]
    planners = ordered(r["planner"] for r in rows)
    tests = ordered(r["test"] for r in rows)
    by = {(r["test"], r["planner"]): r for r in rows}
    lines = [
        "| test | " + " | ".join(planners) + " |",
        "|---|" + "---|" * len(planners),
    ]
    for t in tests:
        cells = []
        for p in planners:
            r = by.get((t, p))
            if r is None:
                cells.append("—")
            else:
                verdict = "**pass**" if r["pass"] else "fail"
                cells.append(f"{verdict}: {cell(r['measured'])}")
        lines.append(f"| `{t}` | " + " | ".join(cells) + " |")
    counts = []
    for p in planners:
        mine = [r for r in rows if r["planner"] == p]
        counts.append(f"{sum(r['pass'] for r in mine)} of {len(mine)}")
    lines.append("| passed | " + " | ".join(counts) + " |")
    total = sum(r["pass"] for r in rows)
    lines.append("")
    lines.append(f"**{total} of {len(rows)} pass** ({len(tests)} tests × {len(planners)} planners).")
    return lines


def number(x, digits=2):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "—"
    text = f"{x:.{digits}f}"
    return "0.00" if text == "-0.00" else text


def nominal(x):
    return f"{x:g}"


def speed_table(report, test, reference_name, reference):
    curves = [c for c in report["curves"] if c["test"] == test and c["name"].endswith("-fd-" + c["planner"])]
    if not curves:
        raise SystemExit(f"validation-tables: the report has no {test} fundamental diagram")
    densities = [row[0] for row in curves[0]["rows"]]
    lines = [
        "| planner | " + " | ".join(nominal(d) for d in densities) + " |",
        "|---|" + "---|" * len(densities),
    ]
    for c in curves:
        col = {name: i for i, name in enumerate(c["columns"])}
        speed = col["speed_m_s"]
        measured = next(i for name, i in col.items() if name.startswith("density_measured_"))
        cells = [f"{number(row[speed])} ({number(row[measured])})" for row in c["rows"]]
        lines.append(f"| {c['planner']} | " + " | ".join(cells) + " |")
    lines.append(f"| {reference_name} | " + " | ".join(number(reference(d)) for d in densities) + " |")
    return lines


def blocks(report):
    return {
        "main": lambda: main_table(report),
        "t4-speeds": lambda: speed_table(report, "t4-fundamental-diagram", "Weidmann", weidmann),
        "t16-speeds": lambda: speed_table(report, "t16-single-file", "Seyfried", seyfried),
    }


def render(report, text):
    """`text` with every marked block replaced by the report's table."""
    for name, make in blocks(report).items():
        begin, end = BEGIN.format(name), END.format(name)
        if begin not in text:
            continue
        head, rest = text.split(begin, 1)
        if end not in rest:
            raise SystemExit(f"validation-tables: {begin} has no {end}")
        _, tail = rest.split(end, 1)
        text = head + begin + "\n" + "\n".join(make()) + "\n" + end + tail
    return text


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    check = "--check" in argv
    if len(args) != 2:
        raise SystemExit(__doc__)
    report_file, doc_file = args
    with open(report_file, encoding="utf-8") as f:
        report = json.load(f)
    with open(doc_file, encoding="utf-8") as f:
        before = f.read()
    after = render(report, before)
    if check:
        if after != before:
            print(f"{doc_file}: tables differ from {report_file}", file=sys.stderr)
            return 1
        print(f"{doc_file}: tables equal {report_file}'s")
        return 0
    with open(doc_file, "w", encoding="utf-8") as f:
        f.write(after)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
