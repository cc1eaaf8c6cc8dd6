#!/usr/bin/env bash
# Installs the Debian packages Tessera needs (only those missing), then configures, builds and
# installs: the `tessera` command into PREFIX/bin, the plot scripts and assets into
# PREFIX/share/tessera, the libraries into PREFIX/lib and the Python package `tessera` where that
# prefix's Python imports from (for ~/.local: the user site of Python 3.x, shared by every Python
# of that version; for another prefix: PREFIX/lib/python3/dist-packages, Debian's).
# Usage: scripts/setup.sh [--with-yade] [--with-sanitizers]   (run as root, or with sudo available)
#        --with-yade also installs YADE, the peer LS-DEM code of bench/peer_yade.sh (large; not
#        needed to build, run or test Tessera); --with-sanitizers clang and its sanitizer and fuzzer
#        runtimes (scripts/sanitize.sh)
# Env:   BUILD_DIR (default: build), BUILD_TYPE (default: Release), JOBS (default: nproc),
#        PREFIX (default: ~/.local; NO_INSTALL=1 builds only)
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
  libglpk-dev                                   # linear programs (tessera check)
  catch2                                        # tests
  python3-matplotlib python3-numpy              # PNG rendering
  python3-dev pybind11-dev                      # the Python module
  python3-pytest python3-h5py                   # its tests; tessera.open_run reads results.h5
  libbenchmark-dev                              # benchmarks (bench/)
  calculix-ccx python3-gmsh                     # finite-element references (bench/validation)
  python3-getfem                                # their large-sliding contact (bench/validation/getfem_*.py)
)
for option in "$@"; do
  case "$option" in
    --with-yade) packages+=(yade python3-h5py python3-numpy) ;;   # bench/peer_yade.sh
    --with-sanitizers) packages+=(clang libclang-rt-dev) ;;       # scripts/sanitize.sh: ASan, UBSan, libFuzzer
    *) echo "setup: unknown option $option (use --with-yade, --with-sanitizers)" >&2; exit 2 ;;
  esac
done

# VTK for Python, with which the tests read the exports back: Debian's python3-vtk9, unless
# /usr/bin/python3 already imports vtkmodules (ParaView's own Python counts) or ParaView's Python
# package is installed (python3-paraview conflicts with python3-vtk9: installing it would remove
# pvpython's modules). Without VTK the two export-reading tests report themselves skipped.
if ! /usr/bin/python3 -c 'import vtkmodules.vtkIOXML' 2>/dev/null; then
  if dpkg-query -W -f='${Status}' python3-paraview 2>/dev/null | grep -q "install ok installed"; then
    echo "setup: python3-paraview is installed and its VTK is not importable by /usr/bin/python3;" \
         "not installing python3-vtk9 (it conflicts); the VTK export tests will be skipped" >&2
  else
    packages+=(python3-vtk9)
  fi
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

prefix=${PREFIX:-"$HOME/.local"}
if [ "$prefix" = "$HOME/.local" ]; then
  python_dir=$(/usr/bin/python3 -c 'import site; print(site.getusersitepackages())')
else
  python_dir="$prefix/lib/python3/dist-packages"
fi
cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type" -DCMAKE_INSTALL_PREFIX="$prefix" \
  -DTESSERA_PYTHON_DIR="$python_dir" -DPython3_EXECUTABLE=/usr/bin/python3
cmake --build "$build_dir" -j "$jobs"
if [ "${NO_INSTALL:-0}" != 1 ]; then
  cmake --install "$build_dir" > /dev/null
  echo "setup: installed $prefix/bin/tessera and the Python package tessera in $python_dir" >&2
fi
