#!/usr/bin/env python3
"""Whether a tool's JSON gives the results a committed one holds: the check that keeps a report in
docs/ from going stale (docs/DIAGNOSIS.md runs it on the Casale diagnosis).

Usage: same_results.py EXPECTED.json ACTUAL.json [--rtol R] [--ignore KEY ...]

Booleans, nulls and the shape of lists and objects must be equal; numbers equal to a relative
tolerance (default 1e-4: the fits end where their tolerances let them, and a build's inlining or
a CPU's libm moves the last bits), or both within ABS_FLOOR of zero (a quantity at a bound of its
fit, eta at 0 or a model on the stability boundary, is zero to the solvers' tolerances; its
digits below are the build's); strings equal in their words, and the numbers written in them
equal to the same tolerance or to one unit of the last decimal printed. Keys named by --ignore are
skipped wherever they occur (default: solver evaluation counts, which follow those last bits).
Prints every difference with its path, exits 1 if there is one.
"""
import argparse
import json
import math
import re
import sys

DEFAULT_IGNORED = ["evaluations", "side_fit_evaluations"]
ABS_FLOOR = 1e-8
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def close(expected, actual, rtol, printed_unit=0.0):
    return math.isclose(expected, actual, rel_tol=rtol, abs_tol=max(ABS_FLOOR, printed_unit))


def last_digit_unit(text):
    """One unit of the last digit a number is printed with: 0.01 for "-0.89", 1e-14 for "2.539e-11";
    0 for a whole number (a count: 9893 samples must stay 9893)."""
    if not any(mark in text.lower() for mark in ".e"):
        return 0.0
    mantissa, _, exponent = text.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 10.0 ** (int(exponent or 0) - decimals)


def same_text(expected, actual, rtol):
    """Equal words, and the numbers in them equal to rtol or to the last digit printed."""
    if NUMBER.split(expected) != NUMBER.split(actual):
        return False
    numbers = list(zip(NUMBER.findall(expected), NUMBER.findall(actual)))
    return all(close(float(e), float(a), rtol, max(last_digit_unit(e), last_digit_unit(a))) for e, a in numbers)


def differences(expected, actual, path, rtol, ignored):
    """Yields (path, expected, actual) for every difference."""
    if isinstance(expected, bool) or isinstance(actual, bool) or expected is None or actual is None:
        if type(expected) is not type(actual) or expected != actual:  # true is not 1, null is not 0
            yield path, expected, actual
    elif isinstance(expected, (int, float)) and isinstance(actual, (int, float)):
        if not close(expected, actual, rtol):
            yield path, expected, actual
    elif isinstance(expected, str) and isinstance(actual, str):
        if not same_text(expected, actual, rtol):
            yield path, expected, actual
    elif isinstance(expected, dict) and isinstance(actual, dict):
        for key in sorted(set(expected) | set(actual)):
            if key in ignored:
                continue
            if key not in expected or key not in actual:
                yield f"{path}/{key}", expected.get(key, "<absent>"), actual.get(key, "<absent>")
            else:
                yield from differences(expected[key], actual[key], f"{path}/{key}", rtol, ignored)
    elif isinstance(expected, list) and isinstance(actual, list):
        if len(expected) != len(actual):
            yield f"{path} (length)", len(expected), len(actual)
        for i, (e, a) in enumerate(zip(expected, actual)):
            yield from differences(e, a, f"{path}[{i}]", rtol, ignored)
    elif expected != actual:
        yield path, expected, actual


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("expected")
    parser.add_argument("actual")
    parser.add_argument("--rtol", type=float, default=1e-4)
    parser.add_argument("--ignore", nargs="*", default=DEFAULT_IGNORED)
    args = parser.parse_args()
    with open(args.expected) as f:
        expected = json.load(f)
    with open(args.actual) as f:
        actual = json.load(f)
    found = list(differences(expected, actual, "", args.rtol, set(args.ignore)))
    for path, e, a in found[:50]:
        print(f"{path}: {args.expected} has {json.dumps(e)[:120]}, {args.actual} has {json.dumps(a)[:120]}")
    if len(found) > 50:
        print(f"... and {len(found) - 50} more")
    print(f"{len(found)} difference(s)" if found else f"same results: {args.actual} gives what {args.expected} holds")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
