#!/usr/bin/env bash
# Installs the Debian (bookworm) packages adb builds against. Called by the Makefile when a
# dependency is missing; safe to run again. Needs root or sudo (a fresh CI machine is root).
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  ccache                   # make test's second build reuses the first one's objects
  libeigen3-dev            # core
  libbullet-dev            # Bullet 3.24, single and double precision (bullet-float64.pc)
  libbullet-extras-dev     # Bullet's HACD: adb-demo's convex-decomposition peer
  libassimp-dev            # mesh files
  libgtest-dev libgmock-dev googletest
  libbenchmark-dev
  libfcl-dev               # peer in the study, oracle in tests
  nlohmann-json3-dev       # scene files
  libcli11-dev             # every executable's command line
  libpng-dev               # adb-demo --render frames
  libtbb-dev               # oneTBB: adb's pair queries on a worker pool (FrameSettings::threads)
  python3-matplotlib       # plots of the study and of the Python examples
  # The Python module (python/, issue 28): built against Debian's /usr/bin/python3, whose
  # numpy and pytest these are; pip, venv, setuptools and wheel install it from a checkout
  # with no package index (pip install --no-build-isolation).
  python3-dev pybind11-dev python3-numpy python3-pytest
  python3-pip python3-venv python3-setuptools python3-wheel
)

# `install-deps.sh fuzz`: also clang and its libFuzzer runtime, for make fuzz only.
if [ "${1:-}" = "fuzz" ]; then
  packages+=(clang libclang-rt-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: everything is installed"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
