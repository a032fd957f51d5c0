#!/usr/bin/env python3
"""check_test_unit_namespaces.py TESTS

Fails (exit 1) when a test source (*_test.cpp) under TESTS, but for folders
*_fixture, opens an anonymous namespace (`namespace {`) instead of
`namespace HQ_TEST_UNIT {`. scripts/test compiles the test sources of a
program in unity batches (HQVIEW_TEST_UNITY, tests/CMakeLists.txt): there
HQ_TEST_UNIT names a namespace of the source's own, while the anonymous
namespaces of a batch's sources are one namespace, in which two helpers of
the same name clash or, worse, one overloads the other.
"""
import pathlib
import re
import sys

ANONYMOUS = re.compile(r"^\s*namespace\s*\{", re.M)


def main():
    root = pathlib.Path(sys.argv[1])
    found = []
    for path in sorted(root.rglob("*_test.cpp")):
        # Not node_modules, nor the fixtures of tests/arch (one has an
        # anonymous namespace on purpose).
        if any(part == "node_modules" or part.endswith("_fixture") for part in path.relative_to(root).parts):
            continue
        text = path.read_text(encoding="utf-8", errors="replace")
        for match in ANONYMOUS.finditer(text):
            line = text.count("\n", 0, match.start()) + 1
            found.append(f"{path.relative_to(root)}:{line}: an anonymous namespace; "
                         "use `namespace HQ_TEST_UNIT {` (tests/CMakeLists.txt, HQVIEW_TEST_UNITY)")
    for problem in found:
        print(problem)
    if not found:
        print(f"no anonymous namespace in the test sources of {root}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
