#!/usr/bin/env bash
# PERI-SISSM set-up: install what is missing, build (or reuse) the pinned LAMMPS, build the
# plugin package against it, and write build/lmp.  Idempotent: a second run only rebuilds the
# project's own sources.
#
# Environment (all optional):
#   LAMMPS_SRC        a LAMMPS source tree (folder holding src/ and cmake/) or a source tarball
#                     to use instead of the pinned one
#   PERI_SISSM_CACHE  where LAMMPS sources and builds are cached (default ~/.cache/peri-sissm)
#   PERI_SISSM_JOBS   parallel build jobs (default: number of cores)
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cache=${PERI_SISSM_CACHE:-$HOME/.cache/peri-sissm}
jobs=${PERI_SISSM_JOBS:-$(nproc)}

# The pinned LAMMPS: stable 29Aug2024 update 2 ("4 Feb 2025"), as Debian packages its source.
lammps_pkg=lammps
lammps_deb_version=20250204+dfsg.1-2
lammps_suite=trixie
lammps_tarball=lammps_20250204+dfsg.1.orig.tar.xz
lammps_sha256=3671165bd52fad36734e0a9136c5bc5ecb225e03988f8c89aa13366a8b53b1c7
lammps_topdir=lammps-4Feb2025

lammps_options=(-DCMAKE_BUILD_TYPE=Release -DBUILD_MPI=on -DBUILD_SHARED_LIBS=on
  -DPKG_PERI=on -DPKG_PLUGIN=on -DWITH_JPEG=on -DWITH_PNG=on -DWITH_GZIP=on)

debian_packages=(cmake g++ make libopenmpi-dev openmpi-bin libeigen3-dev libgtest-dev
  python3-pytest python3-pytest-xdist python3-numpy python3-matplotlib xz-utils ccache
  libjpeg-dev libpng-dev zlib1g-dev ca-certificates python3-sphinx python3-myst-parser libjs-mathjax
  petsc-dev pkg-config valgrind python3-meshio python3-pil)

say() { printf '[setup] %s\n' "$*"; }
die() { printf '[setup] ERROR: %s\n' "$*" >&2; exit 1; }

as_root() {
  if [ "$(id -u)" = 0 ]; then "$@"
  elif command -v sudo >/dev/null; then sudo "$@"
  else die "need root (or sudo) to run: $*"; fi
}

install_packages() {
  local missing=() p
  for p in "${debian_packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' \
      || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then say "Debian packages: all present"; return; fi
  say "Debian packages: installing ${missing[*]}"
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
}

# The machine's own Debian archive address, read from its apt configuration (never written
# into this repository).
debian_archive_uri() {
  local f uri=""
  for f in /etc/apt/sources.list.d/debian.sources; do
    [ -f "$f" ] && uri=$(awk '/^URIs:/ && $2 !~ /security/ {print $2; exit}' "$f")
  done
  if [ -z "$uri" ] && [ -f /etc/apt/sources.list ]; then
    uri=$(awk '$1 == "deb" && $0 !~ /security/ {for (i = 2; i <= NF; i++)
      if ($i ~ /^[a-z]+:\/\//) {print $i; exit}}' /etc/apt/sources.list)
  fi
  [ -n "$uri" ] || die "cannot find a Debian archive in the apt configuration; set LAMMPS_SRC"
  echo "$uri"
}

fetch_pinned_tarball() {
  local dl="$cache/download" tar="$cache/download/$lammps_tarball"
  mkdir -p "$dl"
  if [ -f "$tar" ] && echo "$lammps_sha256  $tar" | sha256sum -c --status; then
    echo "$tar"; return
  fi
  say "fetching the pinned LAMMPS source ($lammps_pkg $lammps_deb_version) from Debian" >&2
  local apt="$cache/apt" uri
  uri=$(debian_archive_uri)
  mkdir -p "$apt/lists/partial" "$apt/archives/partial"
  printf 'deb-src %s %s main\n' "$uri" "$lammps_suite" > "$apt/sources.list"
  local opts=(-o Dir::Etc::SourceList="$apt/sources.list" -o Dir::Etc::SourceParts=/dev/null
    -o Dir::State::Lists="$apt/lists" -o Dir::Cache::Archives="$apt/archives"
    -o APT::Sandbox::User=root)
  apt-get "${opts[@]}" update -qq >&2 || die "apt-get update of the deb-src list failed"
  (cd "$dl" && apt-get -qq "${opts[@]}" source --download-only --tar-only \
    "$lammps_pkg=$lammps_deb_version" >&2) || true
  [ -f "$tar" ] || die "download of $lammps_tarball failed; set LAMMPS_SRC to a LAMMPS tree"
  echo "$lammps_sha256  $tar" | sha256sum -c --status \
    || die "sha256 of $tar does not match the pinned $lammps_sha256"
  echo "$tar"
}

# Prints the path of a LAMMPS source tree (holding src/ and cmake/).
lammps_source_tree() {
  local tarball tree
  if [ -n "${LAMMPS_SRC:-}" ]; then
    if [ -d "$LAMMPS_SRC" ]; then
      [ -f "$LAMMPS_SRC/cmake/CMakeLists.txt" ] || die "LAMMPS_SRC=$LAMMPS_SRC has no cmake/"
      (cd "$LAMMPS_SRC" && pwd); return
    fi
    [ -f "$LAMMPS_SRC" ] || die "LAMMPS_SRC=$LAMMPS_SRC is neither a folder nor a file"
    tarball=$(cd "$(dirname "$LAMMPS_SRC")" && pwd)/$(basename "$LAMMPS_SRC")
    tree="$cache/src/user-$(sha256sum "$tarball" | cut -c1-12)"
  else
    tree="$cache/src/$lammps_topdir"
    [ -f "$tree/.unpacked" ] && { echo "$tree"; return; }
    tarball=$(fetch_pinned_tarball)
  fi
  if [ ! -f "$tree/.unpacked" ]; then
    say "unpacking $(basename "$tarball")" >&2
    rm -rf "$tree.tmp" && mkdir -p "$tree.tmp"
    tar -xf "$tarball" -C "$tree.tmp" --strip-components=1
    rm -rf "$tree" && mv "$tree.tmp" "$tree" && touch "$tree/.unpacked"
  fi
  echo "$tree"
}

lammps_version_of() {
  sed -n 's/^#define LAMMPS_VERSION "\(.*\)"/\1/p' "$1/src/version.h" | tr -d ' '
}

build_lammps() {
  local tree=$1 key bdir
  key="$(lammps_version_of "$tree")-$(printf '%s\n' "$tree" "${lammps_options[@]}" \
    | sha256sum | cut -c1-10)"
  bdir="$cache/build/lammps-$key"
  if [ -x "$bdir/lmp" ] && [ -f "$bdir/.complete" ]; then
    say "LAMMPS: reusing $bdir" >&2; echo "$bdir"; return
  fi
  say "LAMMPS: building in $bdir (about 6 minutes on 2 cores)" >&2
  mkdir -p "$bdir"
  local launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S "$tree/cmake" -B "$bdir" "${lammps_options[@]}" "${launcher[@]}" >"$bdir/configure.log" \
    || die "LAMMPS configure failed, see $bdir/configure.log"
  cmake --build "$bdir" -j "$jobs" >"$bdir/build.log" 2>&1 \
    || die "LAMMPS build failed, see $bdir/build.log"
  touch "$bdir/.complete"
  echo "$bdir"
}

build_project() {
  local tree=$1 lbuild=$2
  say "PERI-SISSM: building in $here/build" >&2
  # ccache in the cache folder, with paths taken relative to the checkout: a fresh clone of the
  # same sources compiles from the cache
  local launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_DIR="$cache/ccache" CCACHE_BASEDIR="$here" CCACHE_NOHASHDIR=1
  cmake -S "$here" -B "$here/build" -DCMAKE_BUILD_TYPE=Release \
    -DLAMMPS_SOURCE_DIR="$tree/src" -DLAMMPS_BINARY_DIR="$lbuild" -DPERISISSM_TESTS=ON \
    "${launcher[@]}" \
    >"$here/build/configure.log" 2>&1 || { cat "$here/build/configure.log"; die "configure failed"; }
  cmake --build "$here/build" -j "$jobs" 2>&1 | tail -n 20
  [ "${PIPESTATUS[0]}" = 0 ] || die "PERI-SISSM build failed"
}

write_wrapper() {
  local lbuild=$1 w="$here/build/lmp"
  cat >"$w" <<WRAP
#!/bin/sh
# Written by tools/setup.sh: LAMMPS (pinned build) with the PERI-SISSM plugin auto-loaded.
export LAMMPS_PLUGIN_PATH="$here/build\${LAMMPS_PLUGIN_PATH:+:\$LAMMPS_PLUGIN_PATH}"
export LD_LIBRARY_PATH="$lbuild\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
# your own potential folders (LAMMPS_POTENTIALS) first, then this package's material files
export LAMMPS_POTENTIALS="\${LAMMPS_POTENTIALS:+\$LAMMPS_POTENTIALS:}$here/potentials"
exec "$lbuild/lmp" "\$@"
WRAP
  chmod +x "$w"
}

# build/python: LAMMPS's own Python module (its files linked from the LAMMPS tree) with the
# shared library it loads beside it, so that PYTHONPATH=build/python makes `from lammps import
# lammps` work (the module looks for liblammps.so in its own folder first)
write_python_module() {
  local tree=$1 lbuild=$2 dir="$here/build/python/lammps" f
  rm -rf "$here/build/python" && mkdir -p "$dir"
  for f in "$tree"/python/lammps/*; do ln -s "$f" "$dir/"; done
  ln -s "$lbuild/liblammps.so" "$dir/liblammps.so"
}

main() {
  install_packages
  local tree lbuild
  tree=$(lammps_source_tree)
  lbuild=$(build_lammps "$tree")
  mkdir -p "$here/build"
  build_project "$tree" "$lbuild"
  write_wrapper "$lbuild"
  write_python_module "$tree" "$lbuild"
  say "ready: $here/build/lmp  (LAMMPS $(lammps_version_of "$tree"), cache $cache)"
}

main "$@"
