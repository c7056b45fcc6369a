"""reference_histories.py — what the comparison scripts of this folder share: a
reference program's CSV and cdyn's history.csv, read row for row (a different number
of rows is a failure)."""
import csv
import os
import sys


def histories(reference_csv, cdyn_out, who):
    """(cdyn's rows, the reference's rows) as lists of dicts of strings."""
    with open(reference_csv) as f:
        reference = list(csv.DictReader(f))
    with open(os.path.join(cdyn_out, "history.csv")) as f:
        cdyn = list(csv.DictReader(f))
    if len(cdyn) != len(reference):
        sys.exit(f"FAIL: {len(cdyn)} cdyn rows against {len(reference)} {who} rows")
    return cdyn, reference
