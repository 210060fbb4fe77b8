# Shared by scripts/build.sh (source it): the checkout's Python package (python/cocopp,
# docs/python.md) on the path of Debian's python3, as `pip install --user -e` would: a .pth
# file naming the checkout's python/ in the user's site-packages, so that every script and
# example imports it without a PYTHONPATH. One file: the checkout built last wins; the ones
# built before stay after it while they exist, so that removing the last (a CI clone in /tmp)
# falls back to the one before instead of to none.
#
#   put_package_on_python_path <checkout root>

put_package_on_python_path() {
  local python_dir user_site pth earlier=()
  python_dir="$(cd "$1" && pwd)/python"
  user_site=$(/usr/bin/python3 -m site --user-site)
  pth="$user_site/cocopp-checkout.pth"
  mkdir -p "$user_site"
  if [ -f "$pth" ]; then
    while IFS= read -r line; do
      if [ "$line" != "$python_dir" ] && [ -d "$line" ]; then earlier+=("$line"); fi
    done < "$pth"
  fi
  printf '%s\n' "$python_dir" "${earlier[@]}" > "$pth"
  echo "build: /usr/bin/python3 imports cocopp from $python_dir ($user_site/cocopp-checkout.pth)"
}
