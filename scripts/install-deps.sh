#!/usr/bin/env bash
# Installs every Debian 12 package simtree needs to build, test, benchmark and run its demo.
# Idempotent: packages already present are skipped, and apt-get update runs at most once.
# Works as root, and through sudo otherwise.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake pkg-config git ca-certificates clang-format
  # numerics and geometry
  libeigen3-dev libspectra-dev libtbb-dev libopen3d-dev libembree-dev
  # baselines for bench/ only (the paper's SAC-IA and FPCS)
  libpcl-dev
  # images, video, tracking
  libopencv-dev libopencv-contrib-dev libavformat-dev libavcodec-dev libavutil-dev libswscale-dev
  ffmpeg
  # RealSense .bag chunks (lz4, bz2)
  liblz4-dev libbz2-dev
  # formats, CLI, logging
  nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev libtinygltf-dev
  # robot simulators for `simtree export` (MuJoCo loads the MJCF; urdfdom, sdformat parse)
  libmujoco-dev liburdfdom-dev libsdformat-dev
  # viewer and headless rendering
  libglfw3-dev libgl-dev libegl-dev libegl-mesa0 libimgui-dev libgl1-mesa-dri xvfb xauth
  # the HTML report: three.js r111 and Chart.js, inlined into report.html (docs/report.md)
  libjs-three libjs-chart.js
  # fuzzing (make fuzz): clang's libFuzzer and sanitizer runtimes
  clang-14 libclang-rt-14-dev
  # tests and benchmarks (chromium: the report's end-to-end test opens it headless)
  libgtest-dev libgmock-dev libbenchmark-dev python3-open3d python3-jsonschema chromium
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: not root and no sudo; install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
