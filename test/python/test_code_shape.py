#!/usr/bin/env python3
"""The house rules a successor keeps, checked on every `make test` (docs/TESTING.md):
- no function in src/ longer than MAX_FUNCTION_LINES lines (short functions that say what they do);
- no tool main (src/tools/*_main.cpp) longer than MAX_MAIN_LINES lines (thin mains: the work is
  the libraries');
- include/acc_identification/<component>/ mirrors src/<component>/: a header's component has sources;
- no production file is named like a test (*_test.cpp, test_*.cpp) under src/;
- no tool option is checked with CLI11's Range, which lets "nan" through (tools/number_checks.h).

Functions are found by their braces: a `{` at namespace level (not a namespace, class, struct,
enum or extern block) opens a function body, whose end is the matching `}`; comments, strings
and character literals are blanked first. A lambda or a nested class counts with its function."""
import os
import re
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import junit_main

PACKAGE = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MAX_FUNCTION_LINES = 120
MAX_MAIN_LINES = 160

_SCOPE = re.compile(r"\b(namespace|class|struct|union|enum)\b[^;()]*$|\bextern\s*$")


def blank_comments_and_literals(text):
    """The text with comments, strings and character literals replaced by spaces (lines kept)."""
    pattern = re.compile(r'//[^\n]*|/\*.*?\*/|R"\((?:.|\n)*?\)"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'',
                         re.S)
    return pattern.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)


def function_lengths(text):
    """[(first_line, lines, header)] of every function body at namespace level in C++ text."""
    code = blank_comments_and_literals(text)
    found, scopes, depth = [], [], 0
    body_start, body_depth, header = None, None, ""
    line, statement = 1, ""
    for ch in code:
        if ch == "\n":
            line += 1
        if ch == "{":
            if body_start is None and depth == len(scopes):
                if _SCOPE.search(statement.strip()):
                    scopes.append(depth)
                else:
                    body_start, body_depth, header = line, depth, " ".join(statement.split())[-80:]
            depth += 1
            statement = ""
        elif ch == "}":
            depth -= 1
            if body_start is not None and depth == body_depth:
                found.append((body_start, line - body_start + 1, header))
                body_start = None
            elif body_start is None and scopes and depth == scopes[-1]:
                scopes.pop()
            statement = ""
        elif ch == ";" and body_start is None:
            statement = ""
        elif body_start is None:
            statement += ch
    return found


def sources(folder, suffixes=(".cpp", ".h")):
    for root, _, names in os.walk(folder):
        for name in sorted(names):
            if name.endswith(suffixes):
                yield os.path.join(root, name)


def relative(path):
    return os.path.relpath(path, PACKAGE)


class CodeShape(unittest.TestCase):
    def test_no_long_function_in_src(self):
        long_ones = []
        for path in sources(os.path.join(PACKAGE, "src")):
            with open(path, encoding="utf-8", errors="replace") as source:
                for first, lines, header in function_lengths(source.read()):
                    if lines > MAX_FUNCTION_LINES:
                        long_ones.append(f"{relative(path)}:{first}: {lines} lines ({header})")
        self.assertEqual(long_ones, [], f"functions longer than {MAX_FUNCTION_LINES} lines")

    def test_tool_mains_are_thin(self):
        fat = []
        for path in sources(os.path.join(PACKAGE, "src", "tools"), (".cpp",)):
            with open(path, encoding="utf-8") as source:
                lines = source.read().count("\n")
            if lines > MAX_MAIN_LINES:
                fat.append(f"{relative(path)}: {lines} lines")
        self.assertEqual(fat, [], f"tool mains longer than {MAX_MAIN_LINES} lines: move the work into a library")

    def test_headers_mirror_sources(self):
        include = os.path.join(PACKAGE, "include", "acc_identification")
        orphans = []
        for component in sorted(os.listdir(include)):
            if os.path.isdir(os.path.join(include, component)) and \
                    not os.path.isdir(os.path.join(PACKAGE, "src", component)):
                orphans.append(component)
        self.assertEqual(orphans, [], "include/acc_identification/<component>/ without src/<component>/")

    def test_no_production_file_named_like_a_test(self):
        named = [relative(path) for path in sources(os.path.join(PACKAGE, "src"))
                 if re.search(r"(^test_|_test\.(cpp|h)$)", os.path.basename(path))]
        self.assertEqual(named, [], "production code named like a test")

    def test_no_option_checked_by_cli11_range(self):
        # Every comparison with NaN is false: CLI::Range(-86400, 86400) passed --time-shift-s nan,
        # and openacc_to_nmea wrote NMEA without times, exit status 0.
        ranged = []
        for folder in ("src", "include"):
            for path in sources(os.path.join(PACKAGE, folder)):
                with open(path, encoding="utf-8", errors="replace") as source:
                    code = blank_comments_and_literals(source.read())
                ranged += [f"{relative(path)}:{code[:match.start()].count(chr(10)) + 1}"
                           for match in re.finditer(r"\bCLI::(Range|PositiveNumber|NonNegativeNumber|Number)\b", code)]
        self.assertEqual(ranged, [], "CLI11 number checks that let nan through: use tools/number_checks.h")

    def test_the_scanner_finds_functions_and_their_lengths(self):
        # Guards the checks above: a scanner that found nothing would pass them all.
        text = ("namespace acc\n{\nnamespace\n{\nstruct S\n{\n  int f() const { return 1; }\n};\n}  // namespace\n"
                "int g(int x)\n{\n  // } a brace in a comment\n  const char* s = \"}\";\n  if (x)\n  {\n"
                "    return 1;\n  }\n  return 0;\n}\n}  // namespace acc\n")
        self.assertEqual([(first, lines) for first, lines, _ in function_lengths(text)], [(7, 1), (11, 9)])
        long_body = "void h()\n{\n" + "  x();\n" * (MAX_FUNCTION_LINES + 5) + "}\n"
        self.assertGreater(function_lengths(long_body)[0][1], MAX_FUNCTION_LINES)
        with open(os.path.join(PACKAGE, "src", "tools", "calibrate_main.cpp"), encoding="utf-8") as main:
            self.assertTrue(any("int main" in header for _, _, header in function_lengths(main.read())))


if __name__ == "__main__":
    junit_main.run(CodeShape)
