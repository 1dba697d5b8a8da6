#!/usr/bin/env bash
# Installs somasim's dependencies (Debian 12 packages) and builds it into build/.
# Usage: scripts/setup.sh [runtime|full]      (as root, or with sudo available)
#   runtime  what running experiments needs: the compiler, CMake, the libraries the CLI and the
#            plugins link (Eigen, yaml-cpp, spdlog, fmt, nlohmann-json, CLI11, OpenCV, Bullet,
#            OSMesa/EGL, assimp, OpenMPI); builds only the `somasim` CLI and its plugins.
#   full     (default) adds what testing and development need: GoogleTest/GoogleMock, Google
#            Benchmark, clang (sanitizers, libFuzzer), clang-format, clang-tidy, Slurm and munge
#            (the local Slurm test), graphviz (`somasim graph | dot`), MuJoCo (the benchmark
#            peer and the MJCF exporter's load test); builds everything (tests, benchmarks, tools).
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-full}"

runtime_packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libyaml-cpp-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libcli11-dev
  libopencv-dev libbullet-dev libosmesa6-dev libegl-dev libegl-mesa0 libassimp-dev
  libcairo2-dev libpango1.0-dev fonts-dejavu-core liburdfdom-dev
  libopenmpi-dev openmpi-bin
)
full_packages=(
  git libgtest-dev libgmock-dev libbenchmark-dev clang-format clang-tidy
  clang libclang-rt-14-dev
  munge slurmctld slurmd slurm-client graphviz
  libmujoco-dev
)
case "$mode" in
  runtime) packages=("${runtime_packages[@]}") ;;
  full) packages=("${runtime_packages[@]}" "${full_packages[@]}") ;;
  *) echo "usage: scripts/setup.sh [runtime|full]" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "== installing: ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
  echo "== packages installed (${SECONDS} s)"
fi

if [ "$mode" = runtime ]; then
  # Only the CLI and the plugins. A build/ that a full setup configured keeps its settings.
  if [ -f build/CMakeCache.txt ]; then
    cmake --build build --parallel "$(nproc)" --target somasim somasim_plugins_all
  else
    echo "== building the CLI and its plugins (build/)"
    cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSOMASIM_WERROR=ON \
      -DSOMASIM_BUILD_TESTS=OFF -DSOMASIM_BUILD_BENCHMARKS=OFF -DSOMASIM_BUILD_TOOLS=OFF \
      -DSOMASIM_PRECOMPILE_HEADERS=ON
    cmake --build build --parallel "$(nproc)"
  fi
  echo "== built (${SECONDS} s)"
  exit 0
fi

echo "== building everything (build/)"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSOMASIM_WERROR=ON \
  -DSOMASIM_BUILD_TESTS=ON -DSOMASIM_BUILD_BENCHMARKS=ON -DSOMASIM_BUILD_TOOLS=ON
cmake --build build --parallel "$(nproc)"
