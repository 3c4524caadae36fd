#!/usr/bin/env bash
# Installs what bsg needs from Debian's packages: the one list of dependencies.
# Idempotent and quick when everything is present. As root it runs apt-get;
# otherwise it prints the exact command to run and exits non-zero.
set -euo pipefail

packages=(
  g++ cmake make pkg-config     # toolchain
  libbullet-dev                 # physics (ships the -float64 libraries we link)
  libeigen3-dev                 # linear algebra for the MLP and trust-region tools
  libopenmpi-dev openmpi-bin    # distributed training, mpirun
  libyaml-cpp-dev               # run and grid configuration files
  libgtest-dev                  # tests
  libcli11-dev                  # the bsg command line
  nlohmann-json3-dev            # JSON output of bsg, golden trajectories in the tests
  python3 python3-matplotlib    # scripts/plot_curves.py: learning curves of a run or a sweep (Figure 2)
  python3-pytest                # Python tests run by ctest: docs check, install, scripts, tests/python
  pybind11-dev python3-dev      # the bsg Python module (python/)
  python3-numpy                 # its arrays
  python3-cloudpickle python3-typing-extensions  # Gymnasium's own needs (conformance tests against it)
  slurm-wlm munge               # bsg sweep --slurm; scripts/slurm_local.sh (a one-node cluster for the tests)
  libegl-dev libopengl-dev      # render/: headless OpenGL through EGL (GLVND)
  libegl-mesa0 libgl1-mesa-dri  # Mesa's EGL driver and llvmpipe, the software rasteriser (no GPU needed)
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev   # MP4 videos, H.264 via Debian's libx264
  libpng-dev                    # PNG pictures and trajectory plots
  libhdf5-dev                   # offline datasets in DSRL's HDF5 format (bsg collect, algos/offline/)
  python3-h5py                  # bsg.datasets.load in Python, reading those files
  clang-14 libclang-rt-14-dev   # libFuzzer targets of the file readers (tests/fuzz/libfuzzer, ctest fuzz.libfuzzer_short)
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

command="apt-get install -y --no-install-recommends ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  echo "install_deps: missing packages: ${missing[*]}" >&2
  echo "install_deps: run as root:  apt-get update && $command" >&2
  exit 1
fi
echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
