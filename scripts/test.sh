#!/usr/bin/env bash
# Set-up + tests: installs what is missing, builds, runs the whole Catch2 suite through CTest, then
# the sanitizer build and its fuzz targets (scripts/sanitize.sh; SKIP_SANITIZE=1 leaves them out).
# Usage: scripts/test.sh [extra ctest arguments]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/setup.sh"
(cd "${BUILD_DIR:-$here/build}" && ctest --output-on-failure -j "${JOBS:-$(nproc)}" "$@")
[ "${SKIP_SANITIZE:-0}" = 1 ] || "$here/scripts/sanitize.sh"
