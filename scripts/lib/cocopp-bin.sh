# Shared by the example scripts (source it): which cocopp to run, so that no script hard-codes
# a relative path to the build tree.
#
#   cocopp=$(cocopp_executable <checkout root>)
# $COCOPP_BIN_DIR/cocopp if set (the tests), else the checkout's build/bin/cocopp, else the
# cocopp on PATH (an install).

cocopp_executable() {
  local root=$1
  if [ -n "${COCOPP_BIN_DIR:-}" ]; then
    echo "$COCOPP_BIN_DIR/cocopp"
  elif [ -x "$root/build/bin/cocopp" ]; then
    echo "$root/build/bin/cocopp"
  elif command -v cocopp > /dev/null; then
    command -v cocopp
  else
    echo "no cocopp: build it (scripts/setup.sh) or put an installed one on PATH" >&2
    return 1
  fi
}
