# Shared by scripts/build.sh (source it): the checkout's Python package (python/cocopp,
# docs/python.md) on the path of Debian's python3, as `pip install --user -e` would: a .pth
# file naming the checkout's python/ in the user's site-packages, so that every script and
# example imports it without a PYTHONPATH. One file: the checkout built last wins.
#
#   put_package_on_python_path <checkout root>

put_package_on_python_path() {
  local python_dir user_site
  python_dir="$(cd "$1" && pwd)/python"
  user_site=$(/usr/bin/python3 -m site --user-site)
  mkdir -p "$user_site"
  echo "$python_dir" > "$user_site/cocopp-checkout.pth"
  echo "build: /usr/bin/python3 imports cocopp from $python_dir ($user_site/cocopp-checkout.pth)"
}
