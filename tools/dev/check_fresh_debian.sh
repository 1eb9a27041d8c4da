#!/usr/bin/env bash
# Checks the README's two commands on a fresh Debian 12 (bookworm) minbase root
# made with debootstrap: a clean clone of HEAD, no ../shared, nothing
# preinstalled but what minbase has. Needs root and debootstrap; takes ~15 min.
#
#   sudo bash tools/dev/check_fresh_debian.sh [ROOTFS_DIR]
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
root="${1:-/tmp/pt-fresh-debian12}"

if [ ! -x "$root/bin/bash" ]; then
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"
mountpoint -q "$root/proc" || mount -t proc proc "$root/proc"
trap 'umount "$root/proc" 2>/dev/null || true' EXIT

rm -rf "$root/root/clone"
git clone -q "$repo" "$root/root/clone"
echo "== README command 1 (showcase)"
chroot "$root" /bin/bash -c 'cd / && bash /root/clone/tools/showcase.sh'
echo "== README command 2 (tests)"
chroot "$root" /bin/bash -c 'cd / && bash /root/clone/tools/test.sh'
echo "fresh Debian 12: both README commands passed"
