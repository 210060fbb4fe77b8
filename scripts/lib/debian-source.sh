# Shared by the install scripts (source it): fetch a Debian source package into a directory,
# through a private apt configuration in build-deps/apt. The system's sources get a deb-src
# twin there only, so the machine's apt set-up stays as it is. Needs dpkg-dev.
#
#   fetch_debian_source <tag> <package> <version> <deps_dir> <destination>
# <tag> prefixes the messages; <destination> (removed first) becomes the unpacked source tree,
# with Debian's patches applied.

fetch_debian_source() {
  local tag=$1 package=$2 version=$3 deps_dir=$4 destination=$5
  local apt_dir=$deps_dir/apt work=$deps_dir/$package-src log=$deps_dir/$package-source.log
  rm -rf "$apt_dir" "$work" "$destination"
  mkdir -p "$apt_dir/sources.list.d" "$apt_dir/lists/partial" "$work"
  local f
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -e "$f" ] || continue
    grep -q 'debian.org' "$f" || continue
    sed 's/^Types:.*/Types: deb-src/' "$f" >"$apt_dir/sources.list.d/$(basename "$f")"
  done
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -e "$f" ] || continue
    grep -E '^deb .*debian.org' "$f" | sed 's/^deb /deb-src /' >>"$apt_dir/sources.list.d/debian-src.list" || true
  done
  local private_apt=(apt-get -q -o Dir::Etc::SourceList=/dev/null
    -o "Dir::Etc::SourceParts=$apt_dir/sources.list.d" -o "Dir::State::Lists=$apt_dir/lists"
    -o Dir::Cache::pkgcache= -o Dir::Cache::srcpkgcache=)
  echo "$tag: fetching the source package $package=$version"
  "${private_apt[@]}" update >"$apt_dir/update.log" 2>&1 || {
    cat "$apt_dir/update.log"
    echo "$tag: apt-get update of the source index failed" >&2
    return 1
  }
  (cd "$work" && "${private_apt[@]}" source "$package=$version" >"$log" 2>&1) || {
    tail -20 "$log"
    echo "$tag: apt-get source $package=$version failed (log: $log)" >&2
    return 1
  }
  local unpacked
  unpacked=$(find "$work" -mindepth 1 -maxdepth 1 -type d | head -1)
  mv "$unpacked" "$destination"
  rm -rf "$work" "$apt_dir/lists"
}
