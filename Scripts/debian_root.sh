# Debian roots for building and testing against another Debian release (sourced by ./run).
#
# A root is made with `debootstrap --variant=minbase` into <dir>.new, gets the package
# list of its flavour installed by ./run itself, and only then is renamed to <dir> with a
# stamp file. A root without a matching stamp (format, release, mirror, package list) or
# any <dir>.new leftover is a half-made or stale root: it is removed and made again,
# never used. Roots live outside the checkout (CI clones afresh for every run).
#
# Entering a root: a private mount namespace (`unshare --mount`), so every bind mount
# disappears with the process, whatever way it ends. The checkout is bind-mounted at the
# same path inside, so build trees and error messages name the same files.

ROOTS_DIR="${PISURFACES_ROOTS_DIR:-/var/cache/pisurfaces}"
ROOT_FORMAT=1
# A new root needs ~5 GB (ParaView and its development packages: 4.2 GB).
ROOT_MIN_FREE_KB=$((5 * 1024 * 1024))

# The Debian archive this machine's apt uses, so that roots come from the same mirror.
debian_mirror() {
  if [ -n "${PISURFACES_MIRROR:-}" ]; then
    echo "$PISURFACES_MIRROR"
    return
  fi
  local uri
  uri="$(cat /etc/apt/sources.list.d/*.sources 2>/dev/null |
    awk '/^URIs:/ { for (i = 2; i <= NF; i++) if ($i ~ /\/debian\/?$/) { print $i; exit } }')"
  if [ -z "$uri" ] && [ -f /etc/apt/sources.list ]; then
    uri="$(awk '$1 == "deb" { for (i = 2; i <= NF; i++) if ($i ~ /\/debian\/?$/) { print $i; exit } }' \
      /etc/apt/sources.list)"
  fi
  echo "${uri:-http://deb.debian.org/debian}"
}

root_fail() {
  local free_kb
  free_kb="$(df -Pk "$ROOTS_DIR" 2>/dev/null | awk 'NR == 2 { print $4 }')"
  if [ -n "$free_kb" ] && [ "$free_kb" -lt $((200 * 1024)) ]; then
    log "FAILED: $1: the disk of $ROOTS_DIR is full ($((free_kb / 1024)) MB free)"
    log "retry: free 5 GB there (or set PISURFACES_ROOTS_DIR), then run the same command again"
    exit 1
  fi
  log "FAILED: $1"
  log "retry: $2"
  exit 1
}

# root_stamp RELEASE FLAVOUR: what a finished root of this kind must record.
root_stamp() {
  local release="$1" flavour="$2"
  printf 'format %s\nrelease %s\nmirror %s\npackages %s\n' "$ROOT_FORMAT" "$release" \
    "$(debian_mirror)" \
    "$(packages_for "$release" "$flavour" | tr ' ' '\n' | sort | sha256sum | cut -c1-16)"
}

# root_run DIR CMD...: run CMD inside the root DIR, the checkout at the same path.
root_run() {
  local dir="$1"
  shift
  cp /etc/resolv.conf "$dir/etc/resolv.conf"
  mkdir -p "$dir$ROOT"
  # The host's /tmp is shared so that `xvfb-run -a` inside sees the displays (X lock
  # files) of the host: abstract X sockets are per network namespace, not per root.
  # ROOT_OVERLAY=1: the root is the lower layer of an overlay whose upper layer is thrown
  # away afterwards, so the cached root stays as it was made (a clean system each time).
  local layer=""
  if [ "${ROOT_OVERLAY:-}" = 1 ]; then
    layer="$(mktemp -d "$ROOTS_DIR/.layer.XXXXXX")"
    mkdir -p "$layer/upper" "$layer/work" "$layer/merged"
  fi
  local status=0
  unshare --mount --propagation private -- /bin/sh -ec '
    dir="$1"; src="$2"; layer="$3"; shift 3
    if [ -n "$layer" ]; then
      mount -t overlay overlay -o "lowerdir=$dir,upperdir=$layer/upper,workdir=$layer/work" "$layer/merged"
      dir="$layer/merged"
    fi
    mount -t proc proc "$dir/proc"
    mount --rbind /dev "$dir/dev"
    mount --rbind /sys "$dir/sys"
    mount --bind /tmp "$dir/tmp"
    mount --bind "$src" "$dir$src"
    exec chroot "$dir" "$@"' sh "$dir" "$ROOT" "$layer" \
    env -i PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=/root \
    LANG=C.UTF-8 TERM="${TERM:-dumb}" CI="${CI:-}" JOBS="$JOBS" "$@" || status=$?
  if [ -n "$layer" ]; then rm -rf --one-file-system "$layer"; fi
  return "$status"
}

# ensure_root RELEASE FLAVOUR: print the directory of a finished root, making it if needed.
ensure_root() {
  local release="$1" flavour="$2"
  local dir="$ROOTS_DIR/$release-$flavour"
  local stamp
  stamp="$(root_stamp "$release" "$flavour")"
  if [ -d "$dir" ] && [ ! -e "$dir.new" ] && [ "$(cat "$dir/.pisurfaces-root" 2>/dev/null)" = "$stamp" ]; then
    echo "$dir"
    return
  fi
  for old in "$dir" "$dir.new"; do
    if [ -e "$old" ]; then
      log "removing the stale or half-made root $old"
      rm -rf --one-file-system "$old"
    fi
  done
  mkdir -p "$ROOTS_DIR" || root_fail "cannot create $ROOTS_DIR" \
    "set PISURFACES_ROOTS_DIR to a writable directory with 5 GB free"
  local free_kb
  free_kb="$(df -Pk "$ROOTS_DIR" | awk 'NR == 2 { print $4 }')"
  if [ "$free_kb" -lt "$ROOT_MIN_FREE_KB" ]; then
    root_fail "only $((free_kb / 1024)) MB free in $ROOTS_DIR; a $release root needs 5 GB" \
      "free space there, or set PISURFACES_ROOTS_DIR to a disk with 5 GB free"
  fi
  local mirror
  mirror="$(debian_mirror)"
  command -v debootstrap >/dev/null || ensure_host_packages debootstrap
  if ! curl -fsS --max-time 30 -o /dev/null "$mirror/dists/$release/Release"; then
    root_fail "the Debian mirror $mirror does not answer for $release ($mirror/dists/$release/Release)" \
      "check the network, or set PISURFACES_MIRROR to a reachable Debian mirror"
  fi
  log "making a Debian $release root in $dir.new from $mirror (debootstrap, ~1 min)"
  if ! debootstrap --variant=minbase "$release" "$dir.new" "$mirror" >"$ROOTS_DIR/$release-$flavour.log" 2>&1; then
    tail -n 15 "$ROOTS_DIR/$release-$flavour.log" >&2
    root_fail "debootstrap of $release from $mirror (log: $ROOTS_DIR/$release-$flavour.log)" \
      "run the same command again; the half-made $dir.new is removed first"
  fi
  log "installing the $flavour packages into the root (~3 min)"
  if ! root_run "$dir.new" env PISURFACES_FLAVOUR="$flavour" "$ROOT/run" install-packages \
    >>"$ROOTS_DIR/$release-$flavour.log" 2>&1; then
    tail -n 15 "$ROOTS_DIR/$release-$flavour.log" >&2
    root_fail "installing packages into the $release root (log: $ROOTS_DIR/$release-$flavour.log)" \
      "run the same command again; the half-made $dir.new is removed first"
  fi
  rm -rf "$dir.new/var/cache/apt/archives/"*.deb
  echo "$stamp" >"$dir.new/.pisurfaces-root"
  mv "$dir.new" "$dir"
  log "root ready: $dir ($(du -sh --one-file-system "$dir" | cut -f1))"
  echo "$dir"
}
