"""One row of the survey's Markdown table, from a `rasterlab check --format
json` report on standard input (see survey.sh).

    python3 survey_row.py NAME START END < report.json
"""

import json
import sys


def mesh(row):
    return f"{row['agreeing']}/{row['total']}" if row else "-"


def main():
    name, seconds = sys.argv[1], float(sys.argv[3]) - float(sys.argv[2])
    try:
        report = json.load(sys.stdin)
    except ValueError:
        print(f"| {name} | (no report: is its library installed?) | | | | |")
        return
    if report["error"]:
        message = report["error"]["message"].splitlines()[0]
        print(f"| {name} | broken: {message} | | | | {seconds:.1f} |")
        return
    table = report["rules"]
    closest = next(r for r in table["rows"] if r["rule"] == table["closest"])
    followed = ", ".join(table["followed"]) or "none"
    print(
        f"| {name} | **{followed}** | {table['closest']} {closest['agreeing']}/{closest['total']} | "
        f"{mesh(table['watertight'])} | {mesh(table['crack_free'])} | {seconds:.1f} |"
    )


if __name__ == "__main__":
    main()
