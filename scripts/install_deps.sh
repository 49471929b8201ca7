#!/usr/bin/env bash
# Installs what hrad needs from Debian bookworm's packages, and does nothing when all is there.
# Usage: scripts/install_deps.sh [--command-only] [--with-notebooks] [--with-fuzzing] [--with-openscenegraph]
#   --command-only: only what building the hrad command and its solves and pictures need
#   (scripts/run.sh); the tests, the benchmarks and the plots of `hrad sweep` and `hrad figures` need
#   the rest, which the default installs too.
#   --with-openscenegraph: install libopenmesh-dev with the OpenSceneGraph headers it depends on (below).
#
# libopenmesh-dev depends on libopenscenegraph-dev for the headers of OpenMesh's OpenSceneGraph kernel,
# which hrad does not include; that dependency alone brings GDAL, Mesa and LLVM to a fresh bookworm:
# 311 packages and 246 MB of downloads with it against 149 and 138 MB without. Where neither is
# installed, an empty local package, hrad-openscenegraph-stand-in ("Provides: libopenscenegraph-dev"),
# satisfies that dependency instead (the way equivs does). Installing libopenscenegraph-dev later
# works as usual; `apt-get remove hrad-openscenegraph-stand-in` removes it (with libopenmesh-dev).
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
with_osg=0
for option in "$@"; do
  case "$option" in
    --command-only) command_only=1 ;;
    --with-notebooks) packages+=(python3-pandas jupyter-nbconvert python3-ipykernel) ;;
    --with-fuzzing) packages+=(clang-14 libclang-rt-14-dev) ;;
    --with-openscenegraph) with_osg=1 ;;
    *) echo "install_deps: unknown option $option" >&2; exit 2 ;;
  esac
done
[[ $command_only -eq 1 ]] || packages+=("${rest[@]}")

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
missing=()
for p in "${packages[@]}"; do
  installed "$p" || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

# The stand-in for libopenscenegraph-dev (above), built where it is needed.
stand_in=()
if [[ $with_osg -eq 0 ]] && ! installed libopenmesh-dev && ! installed libopenscenegraph-dev; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  mkdir -p "$work/pkg/DEBIAN"
  cat > "$work/pkg/DEBIAN/control" <<'CONTROL'
Package: hrad-openscenegraph-stand-in
Version: 1.0
Architecture: all
Maintainer: hrad scripts/install_deps.sh <root@localhost>
Provides: libopenscenegraph-dev
Description: stands in for libopenscenegraph-dev, which libopenmesh-dev depends on
 hrad includes none of OpenMesh's OpenSceneGraph headers. Empty; installed by hrad's
 scripts/install_deps.sh (without --with-openscenegraph).
CONTROL
  chmod 755 "$work"
  dpkg-deb --root-owner-group --build "$work/pkg" "$work/hrad-openscenegraph-stand-in.deb" >/dev/null
  chmod 644 "$work/hrad-openscenegraph-stand-in.deb"
  stand_in=("$work/hrad-openscenegraph-stand-in.deb")
fi

sudo=()
if [[ $(id -u) -ne 0 ]]; then sudo=(sudo); fi
echo "install_deps: installing ${missing[*]}${stand_in:+ (with hrad-openscenegraph-stand-in)}" >&2
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${stand_in[@]}" "${missing[@]}" >&2
