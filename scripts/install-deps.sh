#!/usr/bin/env bash
# Installs the Debian packages listed in scripts/debian-packages.txt that are not installed yet.
# Needs root or sudo only when something is missing; runs `apt-get update` only then.
# Usage: scripts/install-deps.sh [extra-package...]
# With SANDPHYS_MESA_BACKPORTS=1 on Debian 12, Mesa (EGL, GLX and the drivers, llvmpipe and the
# GPUs' alike) comes from bookworm-backports, which it adds to apt's sources: Mesa 25.0 where
# Debian 12 has 22.3, whose llvmpipe runs sandphys faster (bench/README.md, "Mesa from
# backports"). It upgrades the machine's OpenGL drivers, so it is not the default.
set -euo pipefail

script_dir="$(cd -- "$(dirname -- "${BASH_SOURCE[0]}")" && pwd)"
package_list="${script_dir}/debian-packages.txt"

packages=()
while IFS= read -r line; do
  line="${line%%#*}"
  line="${line//[[:space:]]/}"
  if [[ -n "${line}" ]]; then packages+=("${line}"); fi
done <"${package_list}"
packages+=("$@")

if ! command -v dpkg-query >/dev/null 2>&1 || ! command -v apt-get >/dev/null 2>&1; then
  echo "install-deps: this script needs Debian's dpkg and apt-get; install these packages" \
    "yourself:" >&2
  printf '  %s\n' "${packages[@]}" >&2
  exit 1
fi

missing=()
for package in "${packages[@]}"; do
  status="$(dpkg-query --show --showformat='${db:Status-Status}' "${package}" 2>/dev/null || true)"
  [[ "${status}" == "installed" ]] || missing+=("${package}")
done

# Mesa's packages that are not from backports yet (SANDPHYS_MESA_BACKPORTS=1).
backports=()
if [[ "${SANDPHYS_MESA_BACKPORTS:-0}" == 1 ]]; then
  # shellcheck source=/dev/null
  codename="$(. /etc/os-release && echo "${VERSION_CODENAME:-}")"
  if [[ "${codename}" != bookworm ]]; then
    echo "install-deps: SANDPHYS_MESA_BACKPORTS=1 is for Debian 12 (bookworm), not" \
      "'${codename:-unknown}'" >&2
    exit 1
  fi
  for package in libgl1-mesa-dri libegl-mesa0 libglx-mesa0; do
    version="$(dpkg-query --show --showformat='${Version}' "${package}" 2>/dev/null || true)"
    [[ "${version}" == *bpo12* ]] || backports+=("${package}")
  done
fi

if ((${#missing[@]} == 0 && ${#backports[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} Debian packages are installed"
  exit 0
fi

if ((${#missing[@]} > 0)); then echo "install-deps: installing ${missing[*]}"; fi
if ((${#backports[@]} > 0)); then
  echo "install-deps: installing from bookworm-backports: ${backports[*]}"
fi
as_root=()
if ((EUID != 0)); then
  if ! command -v sudo >/dev/null 2>&1; then
    echo "install-deps: not root and sudo is missing; as root, run:" >&2
    if ((${#missing[@]} > 0)); then
      echo "  apt-get update && apt-get install ${missing[*]}" >&2
    fi
    if ((${#backports[@]} > 0)); then
      echo "  and, with bookworm-backports in apt's sources:" >&2
      echo "  apt-get update && apt-get install -t bookworm-backports ${backports[*]}" >&2
    fi
    exit 1
  fi
  # Without a terminal (CI), fail at once instead of waiting for a password.
  if [[ -t 0 ]]; then as_root=(sudo); else as_root=(sudo -n); fi
fi

apt=("${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=300)
if ((${#backports[@]} > 0)) &&
  ! grep -qrsE --include='*.list' --include='*.sources' --include=sources.list \
    '^[^#]*bookworm-backports' /etc/apt/; then
  echo "deb http://deb.debian.org/debian bookworm-backports main" |
    "${as_root[@]}" tee /etc/apt/sources.list.d/bookworm-backports.list >/dev/null
fi
"${apt[@]}" update
if ((${#missing[@]} > 0)); then
  "${apt[@]}" install -y --no-install-recommends "${missing[@]}"
fi
if ((${#backports[@]} > 0)); then
  "${apt[@]}" install -y --no-install-recommends -t bookworm-backports "${backports[@]}"
fi
