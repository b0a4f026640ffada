"""Rows at shared grid times are byte-identical: grid_rows.py REFERENCE.csv CANDIDATE.csv...

REFERENCE is a run sampled every step (--sample-interval equal to the step), so it holds every
grid instant. Each CANDIDATE (the same scene and seed, watched some other way) must have only
rows that REFERENCE has, byte for byte: same time text, same body, same pose digits. Prints the
first difference and exits 1 otherwise. Standard library only.
"""
import sys


def rows(path):
    with open(path, "rb") as f:
        lines = f.read().split(b"\n")
    header, body = lines[0], [l for l in lines[1:] if l]
    table = {}
    for l in body:
        time, key = l.split(b",", 2)[:2]
        table[(time, key)] = l
    return header, table


def main():
    ref_header, ref = rows(sys.argv[1])
    bad = 0
    for path in sys.argv[2:]:
        header, got = rows(path)
        if header != ref_header:
            print(f"{path}: header {header!r} differs from {ref_header!r}")
            bad += 1
            continue
        if not got:
            print(f"{path}: no rows")
            bad += 1
            continue
        for k, line in got.items():
            if k not in ref:
                print(f"{path}: time {k[0].decode()} (body {k[1].decode()}) is not a grid instant of the reference")
                bad += 1
                break
            if ref[k] != line:
                print(f"{path}: differs from the reference at t={k[0].decode()}:\n  {line.decode()}\n  {ref[k].decode()}")
                bad += 1
                break
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
