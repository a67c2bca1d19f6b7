#!/usr/bin/env bash
# Installs everything tmr needs on a Debian bookworm machine and builds PoseLib
# 2.0.5 and COLMAP 4.1.1 into a fixed prefix outside the checkout, from the
# source archives in ../shared/vendor when that folder exists (checked against
# its SHA256SUMS) and otherwise from the repositories' tags (commits checked).
#
# Idempotent: a second run on the same machine checks a few stamps and exits in
# seconds. Needs root (or sudo) for apt-get.
#
# Environment:
#   TMR_DEPS_PREFIX   where COLMAP is installed (default /opt/tmr-deps)
#   TMR_JOBS          parallel build jobs (default 2)
#   TMR_VENDOR_DIR    the source archives with SHA256SUMS (default: the
#                     checkout's ../shared/vendor)
set -euo pipefail

PREFIX="${TMR_DEPS_PREFIX:-/opt/tmr-deps}"
JOBS="${TMR_JOBS:-2}"

PACKAGES=(
  build-essential cmake ninja-build pkg-config git dpkg-dev ca-certificates
  libeigen3-dev libgoogle-glog-dev libgflags-dev libceres-dev
  libfaiss-dev libopenimageio-dev openimageio-tools libglew-dev
  libmetis-dev libsqlite3-dev sqlite3
  libboost-program-options-dev libboost-filesystem-dev libboost-graph-dev
  libboost-system-dev libsuitesparse-dev libgtest-dev libgmock-dev
  libopencv-dev nlohmann-json3-dev clang python3 iproute2 procps
)
# The Slurm test starts its own single-node Slurm from these
# (tests/slurm/local_slurm.sh); the packages' own services are not started.
# Optional: without them that one test is skipped.
SLURM_PACKAGES=(slurmctld slurmd slurm-client munge)
# The report page's test opens report.html in headless Chromium. Optional:
# without it that test is skipped.
BROWSER_PACKAGES=(chromium)

log() { echo "[setup] $*"; }
die() { echo "[setup] error: $*" >&2; exit 1; }

SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || die "run as root or install sudo"
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive

# --- 1. Debian packages ------------------------------------------------------
missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  log "installing ${#missing[@]} Debian packages: ${missing[*]}"
  $SUDO apt-get update -qq || die "apt-get update failed"
  if ! $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/tmp/tmr-apt.log 2>&1; then
    tail -n 20 /tmp/tmr-apt.log >&2
    die "apt-get install failed for: ${missing[*]} (see /tmp/tmr-apt.log)"
  fi
else
  log "Debian packages: all ${#PACKAGES[@]} present"
fi
installed=$(dpkg-query -W -f='${Status}\n' "${SLURM_PACKAGES[@]}" 2>/dev/null |
  grep -c "install ok installed" || true)
if [[ $installed == "${#SLURM_PACKAGES[@]}" ]]; then
  log "Slurm packages: present"
else
  log "installing Slurm packages for the Slurm test: ${SLURM_PACKAGES[*]}"
  # policy-rc.d 101: the packages' services are not started on install.
  guard=""
  if [[ ! -e /usr/sbin/policy-rc.d ]]; then
    guard=/usr/sbin/policy-rc.d
    printf '#!/bin/sh\nexit 101\n' | $SUDO tee "$guard" >/dev/null
    $SUDO chmod +x "$guard"
  fi
  apt_slurm() {
    $SUDO apt-get install -y -qq --no-install-recommends "${SLURM_PACKAGES[@]}" \
      >/tmp/tmr-apt-slurm.log 2>&1
  }
  apt_slurm || { $SUDO apt-get update -qq && apt_slurm; } ||
    log "warning: Slurm packages not installed (see /tmp/tmr-apt-slurm.log); the Slurm test will be skipped"
  [[ -z "$guard" ]] || $SUDO rm -f "$guard"
fi

if dpkg-query -W -f='${Status}' "${BROWSER_PACKAGES[@]}" 2>/dev/null | grep -q "install ok installed"; then
  log "browser for the report page's test: present"
else
  log "installing ${BROWSER_PACKAGES[*]} for the report page's test"
  apt_browser() {
    $SUDO apt-get install -y -qq --no-install-recommends "${BROWSER_PACKAGES[@]}" \
      >/tmp/tmr-apt-browser.log 2>&1
  }
  apt_browser || { $SUDO apt-get update -qq && apt_browser; } ||
    log "warning: ${BROWSER_PACKAGES[*]} not installed (see /tmp/tmr-apt-browser.log); the report page's browser test will be skipped"
fi

# --- 2. PoseLib 2.0.5 and COLMAP 4.1.1 --------------------------------------------
COLMAP4_VERSION="4.1.1"
COLMAP4_COMMIT="a0d785fba74b2664f31edc4a29026a8b27c00f67"
POSELIB_VERSION="2.0.5"
POSELIB_COMMIT="7e9f5f53372e43f89655040d4dfc4a00e5ace11c"
COLMAP4_PREFIX="${PREFIX}/colmap-${COLMAP4_VERSION}"
CHECKOUT="$(cd "$(dirname "$0")/.." && pwd)"
VENDOR_DIR="${TMR_VENDOR_DIR:-${CHECKOUT}/../shared/vendor}"

# Unpacks NAME-VERSION into $SRC_DIR from the vendor archive (checksum checked)
# or clones the tag and checks its commit. Args: name version tag commit url.
fetch_source() {
  local name=$1 version=$2 tag=$3 commit=$4 url=$5
  local tree="${SRC_DIR}/${name}-${version}" archive="${VENDOR_DIR}/${name}-${version}.tar.gz"
  rm -rf "$tree"
  if [[ -f "$archive" ]]; then
    (cd "$VENDOR_DIR" && grep " ${name}-${version}.tar.gz\$" SHA256SUMS | sha256sum -c --status) ||
      die "sha256 mismatch for $archive (or no line for it in ${VENDOR_DIR}/SHA256SUMS)"
    tar -xzf "$archive" -C "$SRC_DIR"
    log "${name} ${version}: from ${archive} (sha256 ok)"
  else
    git clone -q --depth 1 --branch "$tag" "$url" "$tree" 2>/tmp/tmr-git.log ||
      { tail -n 5 /tmp/tmr-git.log >&2; die "cannot clone $url at $tag and no archive at $archive"; }
    [[ $(git -C "$tree" rev-parse HEAD) == "$commit" ]] ||
      die "$url tag $tag is not commit $commit"
    log "${name} ${version}: cloned tag ${tag} (commit checked)"
  fi
}

install_colmap4() {
  local stamp="${COLMAP4_PREFIX}/.tmr-installed"
  if [[ -f "$stamp" && -x "${COLMAP4_PREFIX}/bin/colmap" ]]; then
    log "COLMAP ${COLMAP4_VERSION}: already installed in ${COLMAP4_PREFIX}"
    return 0
  fi
  SRC_DIR="${PREFIX}/src"
  $SUDO mkdir -p "$SRC_DIR"
  $SUDO chown "$(id -u):$(id -g)" "$PREFIX" "$SRC_DIR"
  local start
  start=$(date +%s)
  fetch_source PoseLib "$POSELIB_VERSION" "v${POSELIB_VERSION}" "$POSELIB_COMMIT" \
    https://github.com/PoseLib/PoseLib.git
  local poselib="${SRC_DIR}/PoseLib-${POSELIB_VERSION}"
  log "building PoseLib ${POSELIB_VERSION} into ${COLMAP4_PREFIX}"
  { cmake -S "$poselib" -B "$poselib/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DMARCH_NATIVE=OFF -DCMAKE_INSTALL_PREFIX="$COLMAP4_PREFIX" &&
    cmake --build "$poselib/build" -j "$JOBS" && cmake --install "$poselib/build"; } \
    >"${SRC_DIR}/poselib-build.log" 2>&1 ||
    { tail -n 30 "${SRC_DIR}/poselib-build.log" >&2; die "PoseLib build failed"; }
  rm -rf "$poselib"
  fetch_source colmap "$COLMAP4_VERSION" "$COLMAP4_VERSION" "$COLMAP4_COMMIT" \
    https://github.com/colmap/colmap.git
  local tree="${SRC_DIR}/colmap-${COLMAP4_VERSION}"
  log "configuring COLMAP ${COLMAP4_VERSION} (Release; no GUI, CUDA, ONNX, CGAL, MVS, downloads, tests)"
  cmake -S "$tree" -B "$tree/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$COLMAP4_PREFIX" -DCMAKE_INSTALL_PREFIX="$COLMAP4_PREFIX" \
    -DFETCH_POSELIB=OFF -DFETCH_FAISS=OFF -DFETCH_ONNX=OFF -DONNX_ENABLED=OFF \
    -DGUI_ENABLED=OFF -DCUDA_ENABLED=OFF -DDOWNLOAD_ENABLED=OFF -DCGAL_ENABLED=OFF \
    -DMVS_ENABLED=OFF -DTESTS_ENABLED=OFF >"$tree/configure.log" 2>&1 ||
    { tail -n 30 "$tree/configure.log" >&2; die "COLMAP ${COLMAP4_VERSION} configure failed"; }
  log "building COLMAP ${COLMAP4_VERSION} with ${JOBS} jobs (about 15 minutes on 2 cores)"
  cmake --build "$tree/build" -j "$JOBS" >"$tree/build.log" 2>&1 ||
    { tail -n 30 "$tree/build.log" >&2; die "COLMAP ${COLMAP4_VERSION} build failed (log: $tree/build.log)"; }
  cmake --install "$tree/build" >"$tree/install.log" 2>&1 ||
    die "COLMAP ${COLMAP4_VERSION} install failed"
  "${COLMAP4_PREFIX}/bin/colmap" help >/dev/null 2>&1 ||
    die "installed colmap ${COLMAP4_VERSION} does not run"
  date -u +%FT%TZ >"$stamp"
  rm -rf "$tree"
  log "COLMAP ${COLMAP4_VERSION} installed in ${COLMAP4_PREFIX} ($(( $(date +%s) - start )) s build)"
}

install_colmap4
