#!/usr/bin/env python3
"""check_module_order.py ROOT MODULE...

Fails (exit 1) when a .h or .cpp of ROOT/hqview/<module>/ includes
"hqview/<other>/..." where <other> comes after <module> in the MODULE list
(a module may include only itself and the modules listed before it), when a
module's CMakeLists.txt links an hq_<other> listed after it, or when a folder
of ROOT/hqview is not in the list (one module per folder, one CMake target per
module). The list is lib/hqview/CMakeLists.txt's HQ_MODULES, bottom-up.
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*"hqview/([a-z_0-9]+)/', re.M)
LINK = re.compile(r'\bhq_([a-z_0-9]+)\b')


def problems(root, modules):
    rank = {m: i for i, m in enumerate(modules)}
    base = root / "hqview"
    found = []
    for folder in sorted(p.name for p in base.iterdir() if p.is_dir()):
        if folder not in rank:
            found.append(f"hqview/{folder}/ is not in the module list")
    checked = 0
    for module in modules:
        folder = base / module
        if not folder.is_dir():
            found.append(f"module {module} has no folder hqview/{module}/")
            continue
        for source in sorted(folder.rglob("*")):
            if source.suffix not in (".h", ".cpp"):
                continue
            checked += 1
            name = source.relative_to(root).as_posix()
            for used in INCLUDE.findall(source.read_text(encoding="utf-8", errors="replace")):
                if used not in rank:
                    found.append(f"{name} includes hqview/{used}/, which is not a module")
                elif rank[used] > rank[module]:
                    found.append(f"{name} includes hqview/{used}/ (module {used} comes after {module})")
        cmake = folder / "CMakeLists.txt"
        if cmake.is_file():
            for used in sorted(set(LINK.findall(cmake.read_text()))):
                if used in rank and rank[used] > rank[module]:
                    found.append(f"hqview/{module}/CMakeLists.txt links hq_{used} (module {used} comes after {module})")
    return found, checked


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    root = pathlib.Path(sys.argv[1])
    modules = [m for arg in sys.argv[2:] for m in arg.split(";") if m]
    found, checked = problems(root, modules)
    if found:
        print(f"module order violated (order: {' '.join(modules)}):", file=sys.stderr)
        for p in found:
            print("  " + p, file=sys.stderr)
        return 1
    if checked == 0:
        print(f"no sources under {root}/hqview", file=sys.stderr)
        return 1
    print(f"module order holds: {checked} files of {root}/hqview")
    return 0


if __name__ == "__main__":
    sys.exit(main())
