# shellcheck shell=bash
# Compile through ccache where it is installed (scripts/install-dependencies.sh installs it).
# CI builds a fresh clone three times (Release, sanitizers, fuzz targets), and most of that was
# recompiling files that had not changed since the last run. CCACHE_BASEDIR makes the paths
# inside the clone relative, so a clone in another directory hits the same cache entries;
# CCACHE_NOHASHDIR lets objects with debug information (-g1) hit too, at the price of their
# DW_AT_comp_dir naming the first clone's build directory (source lines still resolve).
# COCOPP_NO_CCACHE=1 compiles without it.
#   source scripts/lib/compiler-cache.sh    # from the repository's root
#   cmake ... "${compiler_cache[@]}"
compiler_cache=(-DCMAKE_C_COMPILER_LAUNCHER= -DCMAKE_CXX_COMPILER_LAUNCHER=)
if [ "${COCOPP_NO_CCACHE:-0}" != 1 ] && command -v ccache >/dev/null; then
  compiler_cache=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true
fi
