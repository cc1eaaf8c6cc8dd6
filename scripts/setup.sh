#!/usr/bin/env bash
# Installs the Debian packages Tessera needs (only those missing), then configures and builds.
# Usage: scripts/setup.sh [--with-yade]   (run as root, or with sudo available)
#        --with-yade also installs YADE, the peer LS-DEM code of bench/peer_yade.sh (large; not
#        needed to build, run or test Tessera)
# Env:   BUILD_DIR (default: build), BUILD_TYPE (default: Release), JOBS (default: nproc)
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-"$here/build"}
build_type=${BUILD_TYPE:-Release}
jobs=${JOBS:-$(nproc)}

# Exactly the packages the build, tests and benchmarks use.
packages=(
  build-essential cmake
  libcgal-dev                                   # mesh validation, exact distances (CGAL)
  libeigen3-dev                                 # linear algebra
  libopenvdb-dev libtbb-dev                     # level sets
  libboost-iostreams-dev                        # needed by OpenVDB's CMake module
  libassimp-dev                                 # mesh import
  libhdf5-dev                                   # asset bundle
  libcli11-dev nlohmann-json3-dev               # command line, JSON output
  libtomlplusplus-dev                           # scene files (TOML)
  catch2                                        # tests
  python3-vtk9 python3-matplotlib               # tests read exports with VTK; PNG rendering
  libbenchmark-dev                              # benchmarks (bench/)
)
if [ "${1:-}" = "--with-yade" ]; then
  packages+=(yade python3-h5py python3-numpy)   # bench/peer_yade.sh
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -q
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type"
cmake --build "$build_dir" -j "$jobs"
