#!/usr/bin/env bash
# Installs every Debian 12 package aperture builds, tests and runs with. Idempotent: quiet when all
# is present, one `apt-get update` only when something is missing. Root runs apt-get directly;
# anyone else goes through sudo.
#   scripts/install-deps.sh          the packages of the build, tests and commands
#   scripts/install-deps.sh fuzz     also clang and its runtime libraries (libFuzzer, sanitizers)
#                                    for `make fuzz` (scripts/fuzz.sh)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config ccache
  libeigen3-dev libopencv-dev libopencv-contrib-dev libtbb-dev
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libnlopt-cxx-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libapriltag-dev libopengv-dev libceres-dev liblinear-dev libpcl-dev
  librosbag-dev librosbag-storage-dev libsensor-msgs-dev
  pybind11-dev python3-dev python3-numpy python3-pytest
  libvisp-dev
  libembree-dev
  visp-images-data
  chromium
  # `make test-slurm` (scripts/slurm/test-single-node.sh): a one-node Slurm with its munge auth.
  slurm-wlm munge
)
if (($# > 1)) || [[ $# -eq 1 && "$1" != fuzz ]]; then
  echo "usage: scripts/install-deps.sh [fuzz]" >&2
  exit 2
fi
if [[ "${1:-}" == fuzz ]]; then
  # libclang-rt-14-dev (libFuzzer, ASan/UBSan runtimes) is only a recommendation of clang.
  packages+=(clang libclang-rt-14-dev)
fi

missing=()
for package in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$package")
done
((${#missing[@]})) || exit 0

if [[ $(id -u) -eq 0 ]]; then
  sudo=()
elif command -v sudo >/dev/null; then
  sudo=(sudo)
else
  echo "install-deps: missing packages (${missing[*]}) and not root, and sudo is not installed." >&2
  echo "install-deps: run this script as root, or install those packages yourself." >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
