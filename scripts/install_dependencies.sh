#!/usr/bin/env bash
# Installs, with apt-get, the Debian packages Poisson_remesh needs to build, test and benchmark.
# Does nothing when they are all present. Needs root (or sudo) only when something is missing.
# Usage: install_dependencies.sh [--minimal]   (--minimal: only what the programs need to build
# and run on CGAL's data set, for the quick start; no test, fuzzing or documentation tools)
set -euo pipefail
minimal=false
[ "${1:-}" = "--minimal" ] && minimal=true

# what the library and the programs need (and CGAL's data set: /usr/share/doc/libcgal-dev/data.tar.gz)
packages=(
  cmake g++ make ccache
  libcgal-dev libboost-dev libeigen3-dev libgmp-dev libmpfr-dev
  libcgal-demo
)
if ! $minimal; then
  packages+=(
    catch2 libtbb-dev
    clang libclang-rt-14-dev   # the libFuzzer targets (scripts/fuzz.sh, ctest fuzz_smoke)
    doxygen                    # the reference documentation (doc target, ctest doc_builds)
  )
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "Installing missing packages: ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then sudo_cmd=(sudo); else
    echo "error: packages missing (${missing[*]}) and not running as root; install them with apt-get." >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
