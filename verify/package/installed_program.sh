#!/bin/sh
# installed_program.sh PREFIX MOVED SOURCE_DIR BUILD_DIR: the installed program
# finds its data relative to itself, with no build or source path compiled in.
set -eu
prefix=$1 moved=$2 source=$3 build=$4
fail() { echo "FAIL: $*" >&2; exit 1; }

# The installed text files name no folder of the build or the source.
for file in "$prefix"/lib/cmake/gearimpact/*.cmake "$prefix"/lib/pkgconfig/gearimpact.pc; do
  if grep -F -e "$source" -e "$build" "$file"; then fail "$file names the build or source tree"; fi
done
# The program had the source tree's paper_data compiled in before; no more.
if grep -a -F -q "$source/paper_data" "$prefix/bin/gearimpact"; then
  fail "$prefix/bin/gearimpact contains $source/paper_data"
fi

# A copy of the prefix elsewhere works as well: everything is relative.
rm -rf "$moved" && mkdir -p "$moved"
moved=$(cd "$moved" && pwd -P)  # as the program sees itself, links resolved
cp -R "$prefix" "$moved/prefix"
"$moved/prefix/bin/gearimpact" reproduce --out "$moved/out" 2>"$moved/reproduce.log" ||
  { cat "$moved/reproduce.log"; fail "reproduce from the moved prefix failed"; }
grep -q "unexplained failures: 0" "$moved/out/REPORT.md" || fail "REPORT.md has failures"

# Without its data the program says where it looked.
rm -rf "$moved/prefix/share"
if "$moved/prefix/bin/gearimpact" reproduce --out "$moved/out2" 2>"$moved/error.txt"; then
  fail "reproduce ran without its data"
fi
grep -F -q "$moved/prefix/share/gearimpact/paper_data/dynamics_statements.csv" "$moved/error.txt" ||
  { cat "$moved/error.txt"; fail "the error does not name where it looked"; }
GEARIMPACT_PAPER_DATA="$moved/nowhere" "$prefix/bin/gearimpact" reproduce --out "$moved/out3" \
  2>"$moved/error2.txt" && fail "reproduce ran with GEARIMPACT_PAPER_DATA pointing nowhere"
grep -F -q "$moved/nowhere (GEARIMPACT_PAPER_DATA)" "$moved/error2.txt" ||
  { cat "$moved/error2.txt"; fail "the error does not name GEARIMPACT_PAPER_DATA"; }
echo "installed program: data found beside it, errors name where it looked"
