#!/usr/bin/env bash
# Runs a command of this checkout inside a fresh Debian 13 (trixie) system:
# a debootstrap chroot made from this system's own Debian apt source (no
# mirror is named here), with a copy of the checkout's files (tracked and
# untracked, not ignored) at /rayglass. What a learner installing Debian 13
# today gets: Mesa 25, GCC 14, Dear ImGui 1.91, the 1.4 validation layer.
# CI (.ci/run) uses it to run the README's two commands there.
#
#   tools/debian13.sh [--root DIR] [--fresh] [--suite bookworm] [COMMAND...]
#
# --suite bookworm makes a fresh Debian 12 instead (a learner's new Debian
# 12 machine: the set-up's time from nothing); use it with its own --root.
# COMMAND (default: tools/setup.sh && tools/test.sh) runs in /rayglass
# as root. The chroot is kept in DIR (default build-debian13/root) and made
# again only with --fresh or when it is missing; the copy of the checkout is
# renewed every time, its build folders kept. proc, sys, dev and a private
# /dev/shm are mounted in a mount namespace of their own, so they vanish
# with the command whatever way it ends. Needs root (debootstrap, chroot).
set -euo pipefail
cd "$(dirname "$0")/.."
top=$PWD

root=build-debian13/root
fresh=0
suite=trixie
while [ $# -gt 0 ]; do
  case "$1" in
    --root) root="$2"; shift ;;
    --fresh) fresh=1 ;;
    --suite)
      case "${2:-}" in trixie | bookworm) suite=$2 ;; *) echo "debian13.sh: --suite trixie or bookworm" >&2; exit 2 ;; esac
      shift ;;
    --) shift; break ;;
    -*) echo "debian13.sh: unknown argument $1" >&2; exit 2 ;;
    *) break ;;
  esac
  shift
done
[ $# -gt 0 ] || set -- bash -c 'tools/setup.sh && tools/test.sh'
if [ "$(id -u)" -ne 0 ]; then
  echo "debian13.sh: needs root (debootstrap and chroot); run it with sudo" >&2
  exit 2
fi
case "$root" in /*) ;; *) root="$top/$root" ;; esac

. tools/lib/apt-source.sh  # debian_uri
if [ "$fresh" = 1 ] || [ ! -x "$root/usr/bin/apt-get" ]; then
  command -v debootstrap >/dev/null || { apt-get update -q && apt-get install -y -q debootstrap; }
  . /etc/os-release
  uri=$(debian_uri "${VERSION_CODENAME:-}" || true)
  if [ -z "$uri" ]; then
    echo "debian13.sh: cannot find this system's Debian apt source to make a $suite system from" >&2
    exit 1
  fi
  rm -rf "$root"
  mkdir -p "$root"
  echo "== debootstrap $suite from $uri into $root"
  start=$SECONDS
  debootstrap --variant=minbase --include=ca-certificates "$suite" "$root" "$uri" >"$root.log" 2>&1 ||
    { tail -n 20 "$root.log"; exit 1; }
  echo "== debootstrap took $((SECONDS - start)) s"
  # No services start inside the chroot (apt's maintainer scripts ask this).
  printf '#!/bin/sh\nexit 101\n' >"$root/usr/sbin/policy-rc.d"
  chmod +x "$root/usr/sbin/policy-rc.d"
fi

# The certificate authorities this machine adds to Debian's (a proxy's, say)
# are trusted inside too, so that what reaches the network here (apt, npm)
# reaches it there.
if compgen -G "/usr/local/share/ca-certificates/*.crt" >/dev/null; then
  mkdir -p "$root/usr/local/share/ca-certificates"
  cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
  chroot "$root" update-ca-certificates >/dev/null 2>&1 || true
fi

# The checkout's files, renewed; build folders inside the chroot stay.
mkdir -p "$root/rayglass"
find "$root/rayglass" -mindepth 1 -maxdepth 1 ! -name 'build*' ! -name out -exec rm -rf {} +
git ls-files -z -co --exclude-standard | tar -c --null --ignore-failed-read -T - 2>/dev/null | tar -x -C "$root/rayglass"

env_vars=(HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8
          NODE_EXTRA_CA_CERTS=/etc/ssl/certs/ca-certificates.crt
          TERM="${TERM:-dumb}" CI="${CI:-}" RG_SANITIZE="${RG_SANITIZE:-}"
          RG_TEST_TIME_SCALE="${RG_TEST_TIME_SCALE:-}")
exec unshare --mount --propagation private -- bash -c '
  set -e
  root=$1; shift
  mount -t proc proc "$root/proc"
  mount -t sysfs sysfs "$root/sys"
  mount --bind /dev "$root/dev"
  mount -t devpts -o newinstance,ptmxmode=0666 devpts "$root/dev/pts"
  mount -t tmpfs -o mode=1777 shm "$root/dev/shm"
  mount -t tmpfs -o mode=1777 tmp "$root/tmp"
  exec chroot "$root" /usr/bin/env -i "$@"
' debian13 "$root" "${env_vars[@]}" bash -c 'cd /rayglass && exec "$@"' bash "$@"
