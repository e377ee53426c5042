#!/usr/bin/env bash
# Rewrites the generated tables of docs/case-files.md from the program's own
# schema (`gearimpact schema`, `gearimpact schema --flags`), after a key or a
# flag was added. verify/io/test_schema.cpp fails until the docs match.
# Usage: scripts/update-docs.sh [PROGRAM] (default build/bin/gearimpact)
set -euo pipefail
cd "$(dirname "$0")/.."
program="${1:-build/bin/gearimpact}"
python3 - "$program" docs/case-files.md <<'PY'
import subprocess, sys
program, path = sys.argv[1], sys.argv[2]
text = open(path).read()
def replace(text, start, end, args):
    out = subprocess.run([program] + args, check=True, capture_output=True, text=True).stdout
    a = text.index(start)
    a = text.index("\n", a) + 1
    b = text.index(end, a)
    return text[:a] + out + text[b:]
text = replace(text, "<!-- schema table:", "<!-- end of schema table -->", ["schema"])
text = replace(text, "<!-- flag table:", "<!-- end of flag table -->", ["schema", "--flags"])
open(path, "w").write(text)
PY
echo "update-docs: docs/case-files.md rewritten from $program"
