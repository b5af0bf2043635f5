"""Reads a CSV file with Python's standard `csv` module and prints its rows as JSON.

Used by the Rust export tests (crates/nodes/tests/it/panel_schedule.rs) to prove that a standard CSV
reader (the one spreadsheets and scripts use) reads the tables cnets writes: quoting, empty cells
and numbers. Usage: python3 scripts/read-csv.py FILE.csv
Exit 0 with a JSON list of rows (each a list of strings); exit 2 when the file cannot be read.
"""
import csv
import json
import sys


def main() -> None:
    if len(sys.argv) != 2:
        sys.stderr.write("usage: python3 scripts/read-csv.py FILE.csv\n")
        sys.exit(2)
    try:
        with open(sys.argv[1], newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f, strict=True))
    except (OSError, csv.Error, UnicodeDecodeError) as e:
        sys.stderr.write("csv could not read the file: %s\n" % e)
        sys.exit(2)
    json.dump(rows, sys.stdout)


if __name__ == "__main__":
    main()
