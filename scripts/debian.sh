#!/usr/bin/env bash
# Run a command in a Debian root of another release that sees this checkout
# at the same path:
#   bash scripts/debian.sh trixie bash scripts/test.sh     # dolfinx 0.9.0
#   bash scripts/debian.sh sid build/piezo-contact --config demos/square.json
# RELEASE is trixie (Debian 13, dolfinx 0.9) or sid (unstable, dolfinx 0.11).
# Each root lives in $PIEZO_ROOTS/RELEASE (default ~/.cache/piezocontact) and
# is made on first use: debootstrap (from Debian's registry), then the
# packages scripts/setup.sh lists for that release; ~5 min and 3.5 GB each.
#
# Inside a root, the checkout's build/ is the host's build-RELEASE/ (and
# build-sanitize/ is build-sanitize-RELEASE/), so the README's commands work
# there unchanged and no release's build overwrites another's. The mounts
# live in a private mount namespace: they vanish with the command, however
# it ends, and never show on the host.
# `scripts/debian.sh --tools` installs the host's debootstrap (if missing)
# and stops: CI does it before anything else can run apt beside it.
set -euo pipefail
usage="usage: scripts/debian.sh trixie|sid [COMMAND...] | --tools"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"

host_tools() {
  command -v debootstrap >/dev/null || {
    $SUDO apt-get update -q
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q debootstrap
  }
}

RELEASE=${1:?$usage}
shift
[ "$RELEASE" != --tools ] || { host_tools; exit 0; }
case "$RELEASE" in
  trixie | sid) ;;
  *) echo "debian.sh: release '$RELEASE' is not trixie or sid; $usage" >&2; exit 2 ;;
esac
CHECKOUT=$(cd "$(dirname "$0")/.." && pwd)
ROOT=${PIEZO_ROOTS:-${HOME:-/root}/.cache/piezocontact}/$RELEASE
MIRROR=${PIEZO_MIRROR:-http://deb.debian.org/debian}
READY=.piezocontact-ready

# Enter the root: proc, sys, dev, the checkout and its build dirs mounted in
# a private namespace; a clean environment (plus what the tests read)
enter() {
  local keep=() v
  for v in TERM PIEZO_BUILD PYTEST_ADDOPTS; do
    [ -n "${!v:-}" ] && keep+=("$v=${!v}")
  done
  mkdir -p "$CHECKOUT/build" "$CHECKOUT/build-$RELEASE" \
           "$CHECKOUT/build-sanitize" "$CHECKOUT/build-sanitize-$RELEASE"
  $SUDO unshare --mount --propagation private -- /bin/bash -euo pipefail -c '
    root=$1 checkout=$2 release=$3; shift 3
    mount -t proc proc "$root/proc"
    mount --rbind /sys "$root/sys"
    mount --rbind /dev "$root/dev"
    mkdir -p "$root$checkout"
    mount --bind "$checkout" "$root$checkout"
    mount --bind "$checkout/build-$release" "$root$checkout/build"
    mount --bind "$checkout/build-sanitize-$release" "$root$checkout/build-sanitize"
    cp /etc/resolv.conf "$root/etc/resolv.conf"
    exec chroot "$root" "$@"' bash "$ROOT" "$CHECKOUT" "$RELEASE" \
    /usr/bin/env -i HOME=/root PATH=/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin \
    LANG=C.UTF-8 OMPI_MCA_btl=self,sm "${keep[@]}" \
    /bin/bash -c 'cd "$0" && exec "$@"' "$CHECKOUT" "$@"
}

make_root() {
  echo "debian.sh: making the $RELEASE root in $ROOT (once; ~5 min, 3.5 GB)" >&2
  host_tools
  # Made aside and moved in place: an interrupted attempt is never taken
  # for a root
  local partial="$ROOT.partial"
  $SUDO rm -rf "$partial"
  $SUDO mkdir -p "$(dirname "$ROOT")"
  $SUDO debootstrap --variant=minbase "$RELEASE" "$partial" "$MIRROR" >&2
  # sid's Release file is valid for a week only: a registry that mirrors it
  # less often (this machine's was 3 weeks old) is otherwise refused
  [ "$RELEASE" != sid ] || echo 'Acquire::Check-Valid-Until "false";' \
    | $SUDO tee "$partial/etc/apt/apt.conf.d/99piezocontact-mirror-age" >/dev/null
  $SUDO rm -rf "$ROOT"
  $SUDO mv "$partial" "$ROOT"
  # The packages: the ones scripts/setup.sh installs on that release
  enter bash scripts/setup.sh --packages-only
  $SUDO touch "$ROOT/$READY"
}

[ -e "$ROOT/$READY" ] || make_root
(($#)) || set -- /bin/bash
enter "$@"
