#!/usr/bin/env bash
# Builds this checkout in a Debian 13 root (FreeCAD 1.0, Python 3.13, nanoflann 1.7) and runs the
# whole suite there: `make test` (C++ and FreeCAD tests), `make demo`, then the pip-installed
# module check.
#
#   bash scripts/test-freecad1.sh          (what `make test-freecad1` runs; needs root)
#
# The root is cached outside the checkout, in $LIFTREMESH_CACHE (default ~/.cache/liftremesh), so
# that a fresh clone (CI) reuses it: debootstrap runs only when it is missing (about 2 minutes),
# and scripts/install-deps.sh, run inside it every time, installs what the deps list added.
# The checkout's files (tracked and untracked, not ignored) are copied into the root with their
# times, so a second run rebuilds only what changed. The mounts are undone however it ends.
set -euo pipefail

source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shared_dir=$(cd "$source_dir/.." && pwd)/shared
cache=${LIFTREMESH_CACHE:-$HOME/.cache/liftremesh}
root=$cache/debian13-root
suite=trixie
jobs=${JOBS:-2}

say() { echo "test-freecad1: $*"; }
fail() { echo "test-freecad1: $*" >&2; exit 1; }

[ "$(id -u)" -eq 0 ] || fail "needs root (debootstrap, chroot and mounts); run it as root or with sudo"

# The Debian mirror apt already uses here (deb822 or one-line sources).
mirror() {
  local uri
  uri=$(grep -hsE '^(URIs:|deb )' /etc/apt/sources.list.d/*.sources /etc/apt/sources.list \
          /etc/apt/sources.list.d/*.list 2>/dev/null \
        | grep -oE 'https?://[^ ]+/debian/?' | grep -v security | head -n1 || true)
  echo "${uri:-http://deb.debian.org/debian}"
}

if [ ! -x "$root/usr/bin/apt-get" ]; then
  if ! command -v debootstrap >/dev/null; then
    say "installing debootstrap"
    DEBIAN_FRONTEND=noninteractive apt-get -q install -y --no-install-recommends debootstrap </dev/null >/dev/null \
      || { apt-get -q update >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get -q install -y \
             --no-install-recommends debootstrap </dev/null >/dev/null; } || fail "could not install debootstrap"
  fi
  say "making a Debian 13 root in $root (debootstrap, about 2 minutes)"
  mkdir -p "$cache"
  rm -rf "$root.partial"
  # Into a side folder first: an interrupted debootstrap never leaves a root that looks whole.
  debootstrap --variant=minbase "$suite" "$root.partial" "$(mirror)" > "$cache/debootstrap.log" 2>&1 \
    || fail "debootstrap failed; its log: $cache/debootstrap.log"
  mv "$root.partial" "$root"
fi

mounted=()
undo_mounts() {
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    umount -l "${mounted[i]}" 2>/dev/null || true
  done
  mounted=()
}
trap undo_mounts EXIT
trap 'exit 130' INT TERM
bind() { # bind SOURCE TARGET [ro]
  mkdir -p "$2"
  mount --bind "$1" "$2"
  mounted+=("$2")
  [ "${3:-}" != ro ] || mount -o remount,bind,ro "$2"
}

mkdir -p "$root/proc" "$root/sys" "$root/dev"
mount -t proc proc "$root/proc" && mounted+=("$root/proc")
bind /sys "$root/sys" ro
bind /dev "$root/dev"
[ ! -d /dev/pts ] || bind /dev/pts "$root/dev/pts"
mkdir -p "$root/dev/shm"
cp -L /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
if [ -d "$shared_dir" ]; then
  bind "$shared_dir" "$root/work/shared" ro
fi

# The checkout, copied (not bound): the build inside writes build/ there, not in this checkout.
work=$root/work/main
mkdir -p "$work"
find "$work" -mindepth 1 -maxdepth 1 ! -name build -exec rm -rf {} +
(cd "$source_dir" && git ls-files -z --cached --others --exclude-standard \
   | xargs -0 -r sh -c 'for f; do [ -e "$f" ] && printf "%s\0" "$f"; done' sh \
   | tar --null -T - -cf -) | tar -xpf - -C "$work"

in_root() {
  chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb CI="${CI:-}" \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin JOBS="$jobs" "$@"
}

say "installing what is missing in the root"
in_root bash /work/main/scripts/install-deps.sh
say "$(in_root sh -c 'grep PRETTY_NAME /etc/os-release; dpkg-query -W freecad-python3 libnanoflann-dev python3' | tr '\n' ' ')"
say "$(in_root freecadcmd -c "import FreeCAD; v = FreeCAD.Version(); print('FreeCAD.Version(): ' + '.'.join(v[:3]) + (' revision ' + v[3] if v[3] else ''))" 2>/dev/null | grep '^FreeCAD.Version' || echo 'FreeCAD does not start')"
say "make test in the root"
in_root make -C /work/main test
say "make demo in the root"
in_root make -C /work/main demo
say "the module installed with pip, used by freecadcmd with no build tree"
in_root bash /work/main/tests/freecad/check_pip_install.sh
say "passed"
