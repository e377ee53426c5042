#!/usr/bin/env python3
"""Checks the library's structure against docs/architecture.md's dependency order.

check_layers.py SOURCE_DIR

1. Every include of a lib/ file that names another concept folder points DOWN the order
   below (a folder may include itself, the folders under it and the shared root headers).
   The order is the one docs/architecture.md states; a folder missing from it fails too.
2. The facade gearimpact/gearimpact.hpp includes every public header of the folders
   and nothing of INTERNAL.
3. What the program (reference/) and the Python module (python/src/) use of the library is
   the facade's: each of their includes of the library names the facade, a header it includes,
   or INTERNAL plumbing, and none reaches into lib/src.
Prints each violation as FILE:LINE and exits 1 when there is one.
"""
import re
import sys
from pathlib import Path

# Bottom to top (signals, numerics and geometry are independent of each other); the root headers (error.hpp, constants.hpp) sit below everything.
ORDER = ["signals", "numerics", "geometry", "contact", "stiffness", "case", "dynamics", "modes", "steady", "batch",
         "io", "paper", "dataset"]
# Public headers that are the program's plumbing, not part of the facade.
INTERNAL = {"io/atomic_file.hpp", "paper/scoring.hpp"}

INCLUDE = re.compile(r'^\s*#\s*include\s+"(?:gearimpact/)?([a-z_]+)/[a-z_0-9]+\.hpp"')


def folder_of(path: Path, lib: Path):
    rel = path.relative_to(lib)
    parts = rel.parts
    # lib/include/gearimpact/<folder>/x.hpp or lib/src/<folder>/x.cpp
    inner = parts[2:] if parts[0] == "include" else parts[1:]
    return inner[0] if len(inner) > 1 else None


def main() -> int:
    source = Path(sys.argv[1])
    lib = source / "lib"
    failures = []
    rank = {name: i for i, name in enumerate(ORDER)}
    edges = set()
    for path in sorted(lib.rglob("*.[ch]pp")):
        here = folder_of(path, lib)
        if here is None:
            continue
        if here not in rank:
            failures.append(f"{path}: folder {here} is not in the dependency order")
            continue
        for number, line in enumerate(path.read_text().splitlines(), 1):
            match = INCLUDE.match(line)
            if not match or match.group(1) == here:
                continue
            there = match.group(1)
            if there not in rank:
                continue  # a file of the same folder in lib/src (event_location.hpp, ...)
            edges.add((here, there))
            if rank[there] > rank[here]:
                failures.append(f"{path}:{number}: {here} includes {there}, which sits above it")

    include_root = lib / "include" / "gearimpact"
    public = {str(p.relative_to(include_root)) for p in include_root.rglob("*.hpp")
              if p.name != "gearimpact.hpp"}
    facade_text = (include_root / "gearimpact.hpp").read_text()
    facade = set(re.findall(r'#include "gearimpact/((?:[a-z_]+/)?[a-z_0-9]+\.hpp)"', facade_text))
    for header in sorted(public - INTERNAL - facade):
        failures.append(f"{include_root / 'gearimpact.hpp'}: does not include public {header}")
    for header in sorted(facade & INTERNAL):
        failures.append(f"{include_root / 'gearimpact.hpp'}: includes internal {header}")
    for header in sorted(facade - public):
        failures.append(f"{include_root / 'gearimpact.hpp'}: includes missing {header}")

    root = lib.parent
    for folder in ("reference", "python/src"):
        for path in sorted((root / folder).rglob("*.[ch]pp")):
            for number, line in enumerate(path.read_text().splitlines(), 1):
                match = re.match(r'^\s*#\s*include\s+"([^"]+)"', line)
                if not match:
                    continue
                name = match.group(1)
                if "lib/src" in name or name.startswith("../"):
                    failures.append(f"{path}:{number}: includes {name}, inside the library")
                elif name.startswith("gearimpact/"):
                    header = name[len("gearimpact/"):]
                    if header != "gearimpact.hpp" and header not in facade | INTERNAL:
                        failures.append(f"{path}:{number}: includes {name}, not in the facade")

    for failure in failures:
        print(failure)
    print("folder edges:", ", ".join(f"{a}->{b}" for a, b in sorted(edges, key=lambda e: (rank[e[0]], rank[e[1]]))))
    print(f"{len(failures)} violation(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
