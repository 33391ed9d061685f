#!/usr/bin/env python3
"""Reads every JUnit XML file under a folder, names each failed or errored test case with its
message, and ends with the line 'tests: N passed, N failed'. Exits 1 when anything failed, a file
cannot be read, or no test case ran at all (an empty suite must never pass)."""
import pathlib
import sys
import xml.etree.ElementTree as ElementTree


def main(folder):
    passed = failed = 0
    for path in sorted(pathlib.Path(folder).rglob("*.xml")):
        try:
            root = ElementTree.parse(path).getroot()
        except ElementTree.ParseError as error:
            print(f"FAILED to read {path}: {error}")
            failed += 1
            continue
        for case in root.iter("testcase"):
            problems = list(case.findall("failure")) + list(case.findall("error"))
            if case.get("status") == "notrun" or case.findall("skipped"):
                continue
            if not problems:
                passed += 1
                continue
            failed += 1
            message = (problems[0].get("message") or problems[0].text or "").strip()
            print(f"FAILED {case.get('classname')}.{case.get('name')} ({path.name}):\n  "
                  + message.replace("\n", "\n  ")[:2000])
    if passed + failed == 0:
        print("no test ran")
    print(f"tests: {passed} passed, {failed} failed")
    return 0 if failed == 0 and passed > 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
