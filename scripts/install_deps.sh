#!/usr/bin/env bash
# Installs what hrad needs from Debian bookworm's packages, and does nothing when all is there.
# Usage: scripts/install_deps.sh [--command-only] [--with-notebooks] [--with-fuzzing]
#   --command-only: only what building the hrad command and its solves and pictures need
#   (scripts/run.sh); the tests, the benchmarks and the plots of `hrad sweep` and `hrad figures` need
#   the rest, which the default installs too.
set -euo pipefail

packages=(
  # toolchain
  g++ make ninja-build cmake pkg-config
  # geometry, meshes, linear algebra, fitting
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev libopenmesh-dev libeigen3-dev libceres-dev libtbb-dev
  # command line, files, formats
  libcli11-dev nlohmann-json3-dev libfmt-dev libpng-dev libopenexr-dev libtinyobjloader-dev libtinygltf-dev libfccp-dev
  # ray casting for the Monte Carlo reference
  libembree-dev
)
rest=(
  # a compiler cache for rebuilds in other trees (an empty one only slows the first build)
  ccache
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev librapidcheck-dev
  # plots written by `hrad sweep` and `hrad figures`
  python3 python3-matplotlib python3-numpy
)
command_only=0
for option in "$@"; do
  case "$option" in
    --command-only) command_only=1 ;;
    --with-notebooks) packages+=(python3-pandas jupyter-nbconvert python3-ipykernel) ;;
    --with-fuzzing) packages+=(clang-14 libclang-rt-14-dev) ;;
    *) echo "install_deps: unknown option $option" >&2; exit 2 ;;
  esac
done
[[ $command_only -eq 1 ]] || packages+=("${rest[@]}")

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

sudo=()
if [[ $(id -u) -ne 0 ]]; then sudo=(sudo); fi
echo "install_deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
