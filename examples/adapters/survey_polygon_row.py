"""One row of the polygon survey's Markdown table, from two `rasterlab
check --kind polygons --keep-going --format json` reports, one a fill rule
(see survey_polygons.sh).

    python3 survey_polygon_row.py NAME SECONDS EVEN_ODD.json NONZERO.json

For each rule: the cases that pass (the top-left convention), then the
cause named (`fill:`, `boundary:`, `hole-ignored`, as `docs/check.md`
lists them) and the failing cases it explains exactly. A cause is named
only where it agrees with the library on the cases that pass too, so the
cases passing plus those explained are the cases on which the library
draws exactly what the reference draws under the cause's changes: the
`follows` column, the better of the two rules.
"""

import json
import sys


def read(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def judged(fill, report):
    """(cell text, (agreeing, total, rule, convention, other changes))."""
    if report is None:
        return "(no report: is its library installed?)", None
    if report["error"]:
        return "broken: " + report["error"]["message"].splitlines()[0], None
    passed, total = report["passed"], report["cases_run"]
    example = report["counterexample"] or {}
    cause = example.get("cause")
    if not cause:
        text = f"{passed}/{total}" + ("" if passed == total else "; no cause named")
        return text, (passed, total, fill, "top-left", [] if passed == total else None)
    explained = sum(f["explained_by_cause"] or 0 for f in report["families"])
    ids = cause["causes"]
    rule = next((c.split(":")[1] for c in ids if c.startswith("fill:")), fill)
    convention = next((c.split(":")[1] for c in ids if c.startswith("boundary:")), "top-left")
    other = [c for c in ids if not c.startswith(("fill:", "boundary:"))]
    text = f"{passed}/{total}; `{' + '.join(ids)}` explains {explained} more"
    return text, (passed + explained, total, rule, convention, other)


def main():
    name, seconds = sys.argv[1], float(sys.argv[2])
    cells, best = [], None
    for fill, path in (("even-odd", sys.argv[3]), ("nonzero", sys.argv[4])):
        text, verdict = judged(fill, read(path))
        cells.append(text)
        if verdict and (best is None or verdict[0] > best[0]):
            best = verdict
    if best is None:
        follows = "-"
    else:
        agreeing, total, rule, convention, other = best
        if other is None:
            # No cause confirmed: the library follows neither rule under
            # any convention of the catalogue.
            follows = f"none (closest: {rule}, {convention} {agreeing}/{total})"
        else:
            changes = "".join(f", {c}" for c in other)
            word = f"{rule}, {convention}{changes}"
            follows = f"**{word}** {agreeing}/{total}" if agreeing == total else f"{word} {agreeing}/{total}"
    print(f"| {name} | {cells[0]} | {cells[1]} | {follows} | {seconds:.1f} |")


if __name__ == "__main__":
    main()
