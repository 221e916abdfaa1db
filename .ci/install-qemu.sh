#!/usr/bin/env bash
# The host tools `cargo xtask firmware` needs: qemu-system-arm (machine mps2-an386) and
# llvm-size/llvm-nm (Debian's `llvm`).
#
# QEMU is NOT installed as a package: on machines that carry a newer qemu-utils (e.g. from
# bookworm-backports, whose qemu-utils Breaks older qemu-system-common), `apt-get install
# qemu-system-arm` would remove or downgrade it. Instead: `apt-get download` the
# qemu-system-arm .deb, unpack it with `dpkg -x` into <repo>/.cache/qemu (git-ignored), and
# `apt-get install` only the shared-library packages it links against that are missing
# (lib* packages, never qemu-*, never an upgrade: if apt would upgrade or remove anything,
# those libraries are unpacked beside QEMU instead).
#
# Idempotent and fast when everything is there (no apt call at all). Prints the path of the
# qemu-system-arm to use on its last line of stdout; everything else goes to stderr.
# Environment: QEMU_CACHE overrides the unpack folder.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dest="${QEMU_CACHE:-$repo/.cache/qemu}"
bin="$dest/usr/bin/qemu-system-arm"
libdirs="$dest/usr/lib/x86_64-linux-gnu:$dest/lib/x86_64-linux-gnu"
export DEBIAN_FRONTEND=noninteractive

SUDO=""
if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1; then SUDO="sudo"; fi
APT=(apt-get -o DPkg::Lock::Timeout=600)

updated=""
apt_update_once() {
    if [ -z "$updated" ]; then
        echo "install-qemu.sh: apt-get update" >&2
        $SUDO "${APT[@]}" update -qq >&2
        updated=1
    fi
}

works() { # $1 = a qemu-system-arm binary
    LD_LIBRARY_PATH="$libdirs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
        timeout 20 "$1" -machine help 2>/dev/null | grep -q '^mps2-an386'
}

# llvm-size / llvm-nm for the size report.
if ! command -v llvm-size >/dev/null 2>&1 || ! command -v llvm-nm >/dev/null 2>&1; then
    apt_update_once
    $SUDO "${APT[@]}" install -y -qq --no-install-recommends llvm >&2
fi

if command -v qemu-system-arm >/dev/null 2>&1 && works "$(command -v qemu-system-arm)"; then
    command -v qemu-system-arm
    exit 0
fi
if [ -x "$bin" ] && works "$bin"; then
    echo "$bin"
    exit 0
fi

apt_update_once
work="$(mktemp -d)"
chmod a+rwx "$work" # apt-get download runs as the _apt user when root
trap 'rm -rf "$work"' EXIT
(cd "$work" && apt-get download qemu-system-arm >&2)
deb="$(ls "$work"/qemu-system-arm_*.deb)"

# The libraries it links against: the lib* names in Depends (first alternative) that are
# not installed yet. Installed ones are left alone (naming them to apt-get install would
# upgrade them, and an upgrade can drag in half the system).
missing=""
for l in $(dpkg-deb -f "$deb" Depends | tr ',' '\n' | sed -e 's/|.*//' -e 's/(.*)//' \
           -e 's/[[:space:]]//g' | grep -E '^lib' || true); do
    if ! dpkg-query -W -f='${Status}' "$l" 2>/dev/null | grep -q 'ok installed'; then
        missing="$missing $l"
    fi
done
extra_debs=""
if [ -n "$missing" ]; then
    # shellcheck disable=SC2086
    plan="$(apt-get install -s -qq --no-install-recommends --no-upgrade $missing)"
    if echo "$plan" | grep -Eq '^(Remv|Inst [^ ]+ \[)'; then
        echo "install-qemu.sh: apt would upgrade/remove packages; unpacking the libraries instead" >&2
        pkgs="$(echo "$plan" | awk '/^Inst /{print $2}')"
        # shellcheck disable=SC2086
        (cd "$work" && apt-get download $pkgs >&2)
        extra_debs="$(ls "$work"/*.deb | grep -v '/qemu-system-arm_' || true)"
    else
        # shellcheck disable=SC2086
        $SUDO "${APT[@]}" install -y -qq --no-install-recommends --no-upgrade $missing >&2
    fi
fi

rm -rf "$dest"
mkdir -p "$dest"
dpkg -x "$deb" "$dest"
for d in $extra_debs; do dpkg -x "$d" "$dest"; done

if ! works "$bin"; then
    echo "install-qemu.sh: unpacked $bin does not run; missing libraries:" >&2
    LD_LIBRARY_PATH="$libdirs" ldd "$bin" | grep 'not found' >&2 || true
    exit 1
fi
echo "$bin"
