#!/bin/sh
# Obtain ODEPACK's double-precision LSODE sources from Debian's *source* package
# `octave` (liboctave/external/odepack/), through a private apt configuration kept
# under the build directory: the system's apt configuration is never changed.
# The downloaded tarball is kept so that later builds do not fetch again.
#
# usage: fetch_odepack.sh BUILD_DIR DEST_DIR
# DEST_DIR receives dlsode.f and the five support routines flexmech compiles
# (DPREPJ and DSOLSY, the Newton matrix, are replaced: src/ode/lsode_newton.f90).
set -eu
build=$(cd "$1" && pwd)
dest=$2
files="dlsode.f dstode.f dintdy.f dcfode.f dewset.f dvnorm.f"

have_all() { for f in $files; do [ -f "$dest/$f" ] || return 1; done; }
have_all && exit 0

apt="$build/apt"
mkdir -p "$apt/etc" "$apt/lists/partial" "$apt/cache/archives/partial" "$apt/src"
. /etc/os-release
suite=${VERSION_CODENAME:?cannot tell the Debian suite from /etc/os-release}
mirror=http://deb.debian.org/debian
keyring=/usr/share/keyrings/debian-archive-keyring.gpg
if [ "${ID:-}" = ubuntu ]; then
  mirror=http://archive.ubuntu.com/ubuntu
  keyring=/usr/share/keyrings/ubuntu-archive-keyring.gpg
  components="main universe"
else
  components=main
fi
echo "deb-src [signed-by=$keyring] $mirror $suite $components" > "$apt/etc/sources.list"
aptopts="-o Dir::Etc::SourceList=$apt/etc/sources.list -o Dir::Etc::SourceParts=/dev/null
 -o Dir::Etc::Preferences=/dev/null -o Dir::Etc::PreferencesParts=/dev/null
 -o Dir::State::Lists=$apt/lists -o Dir::Cache=$apt/cache -o Debug::NoLocking=1
 -o APT::Sandbox::User=root"

tarball=$(ls "$apt/src"/octave_*.orig.tar.* 2>/dev/null | head -n 1 || true)
log="$apt/fetch.log"
if [ -z "$tarball" ]; then
  echo "flexmech: fetching the octave source package for ODEPACK (once; kept in $apt/src; log: $log)" >&2
  # apt's own lines go to the log: it reports the Debian diff or signature it could
  # not fetch ("E: Failed to fetch ... 404"), which is harmless, since only the
  # upstream tarball is needed and its checksum is verified below.
  # shellcheck disable=SC2086
  apt-get $aptopts -qq update > "$log" 2>&1 || true
  # shellcheck disable=SC2086
  (cd "$apt/src" && apt-get $aptopts -qq source --download-only octave) >> "$log" 2>&1 || true
  tarball=$(ls "$apt/src"/octave_*.orig.tar.* 2>/dev/null | head -n 1 || true)
  if [ -z "$tarball" ]; then
    tail -n 20 "$log" >&2
    echo "flexmech: could not download the octave source package (log: $log)" >&2
    exit 1
  fi
fi

# Verify the tarball against the SHA-256 in the package's .dsc.
dsc=$(ls "$apt/src"/octave_*.dsc | head -n 1)
want=$(awk -v f="$(basename "$tarball")" '/^Checksums-Sha256:/{s=1;next} /^[^ ]/{s=0} s && $3==f {print $1}' "$dsc")
got=$(sha256sum "$tarball" | cut -d' ' -f1)
if [ -z "$want" ] || [ "$want" != "$got" ]; then
  echo "flexmech: checksum mismatch for $tarball (want '$want', got '$got')" >&2
  rm -f "$tarball"; exit 1
fi

tmp="$apt/extract"
rm -rf "$tmp"; mkdir -p "$tmp" "$dest"
tar -xf "$tarball" -C "$tmp" --wildcards '*/liboctave/external/odepack/d*.f'
for f in $files; do
  cp "$tmp"/*/liboctave/external/odepack/"$f" "$dest/$f"
done
rm -rf "$tmp"
have_all
echo "flexmech: ODEPACK sources extracted to $dest" >&2
