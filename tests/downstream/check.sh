#!/usr/bin/env bash
# Downstream use of an installed Signorini: installs the build tree into a
# temporary prefix, builds a material plug-in of the suite
# (tests/plugins/scaled_elastic.cc) as a module of a separate CMake project
# with find_package(Signorini), and runs the installed `signorini` on the
# scene of tests/material_plugin.prm.in with that module named in its
# 'Additional shared libraries': exit code 0 and its reference checks
# passed (a failed check exits with 4).
# Usage: check.sh <build dir> <source dir>
set -euo pipefail
build=$1 source=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"

cmake --install "$build" --prefix "$prefix" > "$tmp/install.log" ||
  { cat "$tmp/install.log"; exit 1; }
for f in lib/cmake/Signorini/SignoriniConfig.cmake \
         include/signorini/driver/simulation.h bin/signorini; do
  [[ -e "$prefix/$f" ]] || { echo "not installed: $f"; exit 1; }
done

cmake -S "$source/tests/downstream" -B "$tmp/build" \
  -DSignorini_DIR="$prefix/lib/cmake/Signorini" \
  -DPLUGIN_SOURCE="$source/tests/plugins/scaled_elastic.cc" > "$tmp/configure.log" ||
  { cat "$tmp/configure.log"; exit 1; }
cmake --build "$tmp/build" > "$tmp/build.log" 2>&1 ||
  { tail -40 "$tmp/build.log"; exit 1; }
plugin="$tmp/build/libplugin.so"
[[ -f "$plugin" ]] || { echo "the plug-in module was not built: $plugin"; exit 1; }

# The installed executable loads the module named in the scene of
# tests/material_plugin.prm.in (its closed-form checks: a failed one exits
# with 4) and finds its own library through its RPATH.
mkdir "$tmp/run"
sed "s#^set Additional shared libraries = .*#set Additional shared libraries = $plugin#" \
  "$source/tests/material_plugin.prm.in" > "$tmp/run/scene.prm"
(cd "$tmp/run" && "$prefix/bin/signorini" scene.prm > signorini.log 2>&1) ||
  { tail -20 "$tmp/run/signorini.log"; exit 1; }
passed=$(grep -c "reference check: .*PASS$" "$tmp/run/signorini.log" || true)
[[ "$passed" -ge 4 ]] ||
  { echo "expected 4 passed reference checks, found $passed:"; cat "$tmp/run/signorini.log"; exit 1; }
echo "downstream plug-in: built with find_package(Signorini), loaded by the" \
     "installed signorini, $passed reference checks passed"
