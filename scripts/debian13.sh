#!/usr/bin/env bash
# Run a command in a Debian 13 (trixie: dolfinx 0.9) root that sees this
# checkout at the same path, e.g.
#   bash scripts/debian13.sh bash scripts/test.sh
#   bash scripts/debian13.sh build/piezo-contact --config demos/square.json
# The root lives in $DEBIAN13_ROOT (default ~/.cache/piezocontact/debian13).
# It is made on first use: debootstrap (from Debian's registry), then the
# packages scripts/setup.sh lists for trixie; ~5 min and 3.4 GB.
#
# Inside the root, the checkout's build/ is the host's build-debian13/ (and
# build-sanitize/ is build-sanitize-debian13/), so the README's commands work
# there unchanged and neither release's build overwrites the other's.
# The mounts live in a private mount namespace: they vanish with the command,
# however it ends, and never show on the host.
set -euo pipefail
CHECKOUT=$(cd "$(dirname "$0")/.." && pwd)
ROOT=${DEBIAN13_ROOT:-${HOME:-/root}/.cache/piezocontact/debian13}
MIRROR=${DEBIAN13_MIRROR:-http://deb.debian.org/debian}
READY=.piezocontact-ready

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"

# Enter the root: proc, sys, dev, the checkout and its build dirs mounted in
# a private namespace; a clean environment (plus what the tests read)
enter() {
  local keep=() v
  for v in TERM PIEZO_BUILD PYTEST_ADDOPTS; do
    [ -n "${!v:-}" ] && keep+=("$v=${!v}")
  done
  mkdir -p "$CHECKOUT/build" "$CHECKOUT/build-debian13" \
           "$CHECKOUT/build-sanitize" "$CHECKOUT/build-sanitize-debian13"
  $SUDO unshare --mount --propagation private -- /bin/bash -euo pipefail -c '
    root=$1 checkout=$2; shift 2
    mount -t proc proc "$root/proc"
    mount --rbind /sys "$root/sys"
    mount --rbind /dev "$root/dev"
    mkdir -p "$root$checkout"
    mount --bind "$checkout" "$root$checkout"
    mount --bind "$checkout/build-debian13" "$root$checkout/build"
    mount --bind "$checkout/build-sanitize-debian13" "$root$checkout/build-sanitize"
    cp /etc/resolv.conf "$root/etc/resolv.conf"
    exec chroot "$root" "$@"' bash "$ROOT" "$CHECKOUT" \
    /usr/bin/env -i HOME=/root PATH=/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin \
    LANG=C.UTF-8 OMPI_MCA_btl=self,sm "${keep[@]}" \
    /bin/bash -c 'cd "$0" && exec "$@"' "$CHECKOUT" "$@"
}

make_root() {
  echo "debian13: making the Debian 13 root in $ROOT (once; ~5 min, 3.4 GB)" >&2
  command -v debootstrap >/dev/null || {
    $SUDO apt-get update -q
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q debootstrap
  }
  # Made aside and moved in place: an interrupted attempt is never taken
  # for a root
  local partial="$ROOT.partial"
  $SUDO rm -rf "$partial"
  $SUDO mkdir -p "$(dirname "$ROOT")"
  $SUDO debootstrap --variant=minbase trixie "$partial" "$MIRROR" >&2
  $SUDO rm -rf "$ROOT"
  $SUDO mv "$partial" "$ROOT"
  # The packages: the ones scripts/setup.sh installs on Debian 13
  enter bash scripts/setup.sh --packages-only
  $SUDO touch "$ROOT/$READY"
}

[ -e "$ROOT/$READY" ] || make_root
(($#)) || set -- /bin/bash
enter "$@"
