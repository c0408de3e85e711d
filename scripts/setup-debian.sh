#!/usr/bin/env bash
# Installs every Debian 12 package rockmass needs to build, test and run.
# Idempotent: packages already installed are skipped, and apt-get is not
# called at all when nothing is missing; then the tests' glTF validator (npm).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev          # geometry, dda3d: dense linear algebra
  libyaml-cpp-dev        # io: scene files
  libcli11-dev           # app: command line
  nlohmann-json3-dev     # io: summary.json
  libtbb-dev             # parallel loops
  zlib1g-dev             # io: VTU arrays compressed as VTK compresses them
  libembree-dev          # rqd: ray casting of scanlines through the discs
  libopenvdb-dev libboost-iostreams-dev   # rqd: RQD and P32 volumes (OpenVDB grids)
  libcgal-dev libgmp-dev libmpfr-dev   # blocks: exact Nef polyhedra
  libassimp-dev          # blocks, io: mesh domains and block meshes
  libtinygltf-dev        # io: the blocks as glb
  libsuitesparse-dev     # dda3d: CHOLMOD sparse Cholesky
  libatlas3-base         # dda3d: CHOLMOD's BLAS and LAPACK (ATLAS, base x86-64; CMakeLists.txt)
  libboost-dev           # ensemble: Boost.Math distributions (quantiles)
  libopenmpi-dev openmpi-bin   # ensemble: realizations over MPI ranks (optional at build time)
  pybind11-dev python3-dev python3-pytest   # python/: the rockmass module and its tests
  libjs-three            # run: report.html's 3D viewer (three.js, inlined)
  chromium               # tests: report.html opened in headless Chromium
  python3-matplotlib python3-numpy     # figures from the CSV outputs
  python3-meshio python3-vtk9   # tests: the VTU files read by meshio and by VTK
  libgtest-dev libgmock-dev   # tests
  libbenchmark-dev       # bench
  clang-14 libclang-rt-14-dev   # fuzz: libFuzzer targets of the input readers
  clang-format-14        # tests: the formatting check
  nodejs                 # tests: Khronos' glTF validator (npm, below) reads the glb
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
else
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Khronos' glTF validator (the npm package, pinned) for the tests of blocks.glb, in
# tools/node/ of the source tree (not tracked). Without the npm registry the glb test fails
# and says so; nothing else needs it.
validator_version=2.0.0-dev.3.10
validator=tools/node/node_modules/gltf-validator/package.json
if ! grep -q "\"version\": \"$validator_version\"" "$validator" 2>/dev/null; then
  echo "setup: installing gltf-validator $validator_version (npm) into tools/node"
  if ! npm install --prefix tools/node --no-save --no-audit --no-fund --silent \
    "gltf-validator@$validator_version"; then
    echo "setup: warning: npm could not install gltf-validator; the glb test will fail" >&2
  fi
fi
