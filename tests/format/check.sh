#!/usr/bin/env bash
# The sources are a fixed point of clang-format 14 (Debian 12's) with the
# repository's .clang-format: every C++ file of include/, source/ and tests/
# formats to itself. Other major versions format differently, so the
# version is pinned. To fix a failure: `make -C build format` (or
# clang-format -i on the files listed).
# Usage: check.sh <source dir>
set -euo pipefail
top=$1
clang_format=$(command -v clang-format-14 || command -v clang-format || true)
if [[ -z "$clang_format" ]]; then
  echo "clang-format is not installed: apt-get install clang-format (Debian 12: version 14)"
  exit 1
fi
version=$("$clang_format" --version)
if [[ ! "$version" =~ version\ 14\. ]]; then
  echo "the format is defined by clang-format 14 (Debian 12); found: $version"
  exit 1
fi
cd "$top"
mapfile -t files < <(find include source tests \
  \( -name '*.cc' -o -name '*.h' \) -not -path 'tests/downstream/*' | sort)
bad=()
for f in "${files[@]}"; do
  "$clang_format" --style=file "$f" | cmp -s - "$f" || bad+=("$f")
done
if (( ${#bad[@]} > 0 )); then
  echo "${#bad[@]} of ${#files[@]} files are not formatted (clang-format -i):"
  printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "${#files[@]} files formatted as clang-format 14 formats them"
