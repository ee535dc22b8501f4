#!/usr/bin/env bash
# Checks the C++ sources under sandphys/ samples/ bench/ tests/ bridge/ against .clang-format
# and lists every file that needs formatting. With --fix, formats them in place instead.
# Usage: scripts/check-format.sh [--fix]     (CLANG_FORMAT=... selects the binary)
set -euo pipefail

cd -- "$(dirname -- "${BASH_SOURCE[0]}")/.."

fix=false
case "${1:-}" in
  "") ;;
  --fix) fix=true ;;
  *) echo "usage: $0 [--fix]" >&2; exit 2 ;;
esac

clang_format="${CLANG_FORMAT:-clang-format}"
if ! command -v "${clang_format}" >/dev/null 2>&1; then
  echo "check-format: ${clang_format} not found (Debian package clang-format)" >&2
  exit 1
fi

dirs=(sandphys samples bench tests bridge)
files=()
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  # Tracked files plus new ones not yet added, minus what .gitignore excludes.
  while IFS= read -r -d '' file; do
    if [[ -f "${file}" ]]; then files+=("${file}"); fi
  done < <(git ls-files -z --cached --others --exclude-standard -- \
    "${dirs[@]/%//*.h}" "${dirs[@]/%//*.hpp}" "${dirs[@]/%//*.cpp}" "${dirs[@]/%//*.cc}" \
    "${dirs[@]/%//*.inl}" | sort -zu)
else
  existing=()
  for dir in "${dirs[@]}"; do
    if [[ -d "${dir}" ]]; then existing+=("${dir}"); fi
  done
  if ((${#existing[@]} > 0)); then
    while IFS= read -r -d '' file; do files+=("${file}"); done < <(
      find "${existing[@]}" -type f \( -name '*.h' -o -name '*.hpp' -o -name '*.cpp' \
        -o -name '*.cc' -o -name '*.inl' \) -print0 | sort -z)
  fi
fi

if ((${#files[@]} == 0)); then
  # sandphys/ alone has dozens; finding none means the listing above went wrong.
  echo "check-format: no C++ files found under ${dirs[*]}" >&2
  exit 1
fi

if ${fix}; then
  "${clang_format}" -i --style=file "${files[@]}"
  echo "check-format: formatted ${#files[@]} files"
  exit 0
fi

unformatted=()
for file in "${files[@]}"; do
  if ! "${clang_format}" --style=file "${file}" | cmp -s - "${file}"; then
    unformatted+=("${file}")
  fi
done

if ((${#unformatted[@]} > 0)); then
  echo "check-format: ${#unformatted[@]} of ${#files[@]} files need formatting" \
    "($("${clang_format}" --version)):" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  echo "fix with: scripts/check-format.sh --fix" >&2
  exit 1
fi
echo "check-format: ${#files[@]} C++ files are formatted"
