#!/usr/bin/env bash
# README.md quotes samples/hello_sand/main.cpp verbatim between the lines `<!-- hello_sand -->`
# and `<!-- /hello_sand -->`. Checks that the quote matches the file; --fix rewrites the quote.
# Usage: scripts/check-readme.sh [--fix]
set -euo pipefail

cd -- "$(dirname -- "${BASH_SOURCE[0]}")/.."

readme=README.md
source_file=samples/hello_sand/main.cpp
begin='<!-- hello_sand -->'
end='<!-- /hello_sand -->'

fix=false
case "${1:-}" in
  "") ;;
  --fix) fix=true ;;
  *) echo "usage: $0 [--fix]" >&2; exit 2 ;;
esac

if [[ ! -f "${source_file}" ]]; then
  echo "check-readme: ${source_file} is missing" >&2
  exit 1
fi
if [[ "$(grep -cxF -e "${begin}" -e "${end}" "${readme}")" != 2 ]]; then
  echo "check-readme: ${readme} needs exactly one '${begin}' ... '${end}' block" >&2
  exit 1
fi

# README with the block's content replaced by the current source, fenced as C++.
expected="$(mktemp)"
trap 'rm -f -- "${expected}"' EXIT
awk -v begin="${begin}" -v end="${end}" -v src="${source_file}" '
  $0 == begin { print; print "```cpp"; while ((getline line < src) > 0) print line; print "```";
                skip = 1; next }
  $0 == end { skip = 0 }
  !skip { print }
' "${readme}" >"${expected}"

if cmp -s "${expected}" "${readme}"; then
  echo "check-readme: ${readme} quotes ${source_file} verbatim"
elif ${fix}; then
  cp -- "${expected}" "${readme}"
  echo "check-readme: updated the quote of ${source_file} in ${readme}"
else
  echo "check-readme: ${readme} does not quote ${source_file} verbatim:" >&2
  diff -u "${readme}" "${expected}" >&2 || true
  echo "fix with: scripts/check-readme.sh --fix" >&2
  exit 1
fi
