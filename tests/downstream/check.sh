#!/usr/bin/env bash
# Downstream use of an installed Signorini: installs the build tree into a
# temporary prefix, builds a program of the suite (a material plug-in defined
# outside the library, tests/material_plugin.cc) as a separate CMake project
# with find_package(Signorini), runs it, and compares its output with that
# test's expected output (numdiff, the tolerances of the suite). Also runs
# the installed `signorini` executable on a scene with reference checks: exit
# code 0 means they passed (a failed check exits with 4).
# Usage: check.sh <build dir> <source dir> <numdiff>
set -euo pipefail
build=$1 source=$2 numdiff=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"

cmake --install "$build" --prefix "$prefix" > "$tmp/install.log" ||
  { cat "$tmp/install.log"; exit 1; }
for f in lib/cmake/Signorini/SignoriniConfig.cmake \
         include/signorini/core/simulation.h bin/signorini; do
  [[ -e "$prefix/$f" ]] || { echo "not installed: $f"; exit 1; }
done

cmake -S "$source/tests/downstream" -B "$tmp/build" \
  -DSignorini_DIR="$prefix/lib/cmake/Signorini" \
  -DPROGRAM_SOURCE="$source/tests/material_plugin.cc" > "$tmp/configure.log" ||
  { cat "$tmp/configure.log"; exit 1; }
cmake --build "$tmp/build" > "$tmp/build.log" 2>&1 ||
  { tail -40 "$tmp/build.log"; exit 1; }

mkdir "$tmp/run"
(cd "$tmp/run" && "$tmp/build/downstream")
"$numdiff" -a 1e-6 -r 1e-8 -s ' \t\n:<>=,;' -q \
  "$tmp/run/output" "$source/tests/material_plugin.output" ||
  { echo "downstream output differs from tests/material_plugin.output:";
    diff "$tmp/run/output" "$source/tests/material_plugin.output"; exit 1; }

# The installed executable finds its library (RPATH) and its run of the
# contact patch test passes the test's reference checks.
(cd "$tmp/run" && "$prefix/bin/signorini" "$source/tests/contact_patch_2d.prm" \
   > signorini.log 2>&1) ||
  { tail -20 "$tmp/run/signorini.log"; exit 1; }
echo "downstream program: output as tests/material_plugin.output;" \
     "installed signorini ran tests/contact_patch_2d.prm"
