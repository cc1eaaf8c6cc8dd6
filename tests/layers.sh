#!/usr/bin/env bash
# The layers point one way, and the kernel links no file format.
#   io <- geometry <- levelset <- solver (kernel) <- run <- tools, python
# Each folder's sources may include only their own folder and the folders below; the kernel
# (solver/) only the data types of geometry/ and levelset/ (headers), never io/, and its shared
# library needs no HDF5, OpenVDB, assimp, CGAL, TOML or JSON.
# Usage: layers.sh SOURCE_DIR KERNEL_LIBRARY
set -euo pipefail
source_dir=$1 kernel=$2
declare -A allowed=(
  [io]="io"
  [geometry]="io geometry"
  [levelset]="io geometry levelset"
  [solver]="geometry levelset solver"
  [run]="io geometry levelset solver run"
  [tools]="io geometry levelset solver run tools"
  [python]="io geometry levelset solver run python"
)
status=0
for folder in "${!allowed[@]}"; do
  while IFS= read -r line; do
    file=${line%%:*}
    included=$(sed -E 's/.*#include "([a-z_]+)\/.*/\1/' <<<"$line")
    if [[ " ${allowed[$folder]} " != *" $included "* ]]; then
      echo "layers: $file includes $included/, above or beside $folder/ (${line#*:})"
      status=1
    fi
  done < <(cd "$source_dir" && grep -H -E '^#include "[a-z_]+/' "$folder"/*.h "$folder"/*.cpp 2>/dev/null || true)
done
# The kernel's API: the layers above it include only its public headers (world.h and what it
# includes), and those include no other solver header, so that the solver's own records
# (pair_contacts.h, node_contacts.h, world_internals.h, ...) stay private to it and its tests.
public="world.h contact_parameters.h solver_settings.h pair_view.h pair_state.h rigid_bodies.h obstacles.h contact_bars.h travel.h"
while IFS= read -r line; do
  header=$(sed -E 's/.*#include "solver\/([a-z_]+\.h)".*/\1/' <<<"$line")
  if [[ " $public " != *" $header "* ]]; then
    echo "layers: ${line%%:*} includes solver/$header, which is private to the solver (public: $public)"
    status=1
  fi
done < <(cd "$source_dir" && grep -H -E '^#include "solver/' run/*.h run/*.cpp tools/*.h tools/*.cpp python/*.h python/*.cpp \
           $(for h in $public; do echo solver/$h; done) 2>/dev/null || true)
# The kernel: no file-format headers in its sources, none among the libraries it needs.
if grep -l -E '#include <(hdf5|toml\+\+|nlohmann|openvdb|assimp|CGAL)' "$source_dir"/solver/*.h "$source_dir"/solver/*.cpp; then
  echo "layers: the kernel (solver/) includes a file-format library"
  status=1
fi
needed=$(readelf -d "$kernel" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
for library in $needed; do
  case "$library" in
    # ld-linux: glibc's loader, which provides thread-local storage (the kernel's per-thread scratch).
    libtbb*|libstdc++*|libm.*|libgcc_s*|libc.*|ld-linux*) ;;
    *) echo "layers: the kernel $kernel needs $library (only TBB and the C/C++ runtime are allowed)"; status=1 ;;
  esac
done
# Every call the kernel makes into Tessera is into itself: a tessera:: symbol it leaves undefined
# would be resolved at load time from a library above it, which its NEEDED entries do not show.
undefined=$(nm -D --undefined-only "$kernel" | c++filt | grep -E ' tessera::' || true)
if [ -n "$undefined" ]; then
  echo "layers: the kernel $kernel calls Tessera code it does not contain:"
  echo "$undefined"
  status=1
fi
[ $status = 0 ] && echo "layers: one way; the kernel needs only: $(echo $needed | tr '\n' ' ')"
exit $status
