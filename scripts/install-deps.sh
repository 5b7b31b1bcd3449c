#!/usr/bin/env bash
# Installs the Debian packages viscolube needs, only those missing.
# Non-interactive and idempotent: silent and fast when everything is present.
set -euo pipefail
packages=(build-essential cmake pkg-config libsundials-dev libgsl-dev libsqlite3-dev
          libcmocka-dev libinih-dev liblapack-dev libopenblas-dev libfftw3-dev
          libplplot-dev plplot-driver-cairo fonts-dejavu-core
          libopenmpi-dev openmpi-bin # `viscolube study` under mpirun (optional in the build)
          clang libclang-rt-14-dev # scripts/fuzz.sh: clang 14 and its libFuzzer runtime
          clang-format             # scripts/format.sh
          universal-ctags          # scripts/api-users.py
          python3-dev python3-numpy) # the Python package (python/)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "installing: ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
