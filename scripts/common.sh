# Shared by scripts/demo, scripts/test and scripts/bench: install what is missing, configure
# and build (incrementally) in build/.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${STRATA_BUILD_DIR:-$ROOT/build}"
PACKAGES="cmake ninja-build g++ clang-format universal-ctags libvtk9-dev python3-vtk9 python3-dev python3-numpy libglm-dev libegl-dev libegl-mesa0 libgl1-mesa-dri pocl-opencl-icd ocl-icd-opencl-dev opencl-headers libzstd-dev libsegyio-dev"

strata_install() {
  local missing=()
  for p in $PACKAGES; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "Installing: ${missing[*]}"
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -q
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
  fi
}

strata_build() {
  strata_install
  if [ ! -f "$BUILD/build.ninja" ]; then
    cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release
  fi
  cmake --build "$BUILD" -j "$(nproc)"
}
