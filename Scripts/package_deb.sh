#!/usr/bin/env bash
# Makes the .deb of PiSurfaces for the running Debian from a finished build tree:
#   Scripts/package_deb.sh <build dir> <output dir>
# The plugin goes where that system's ParaView finds it without a path, the `pisurfaces`
# Python package where its pvpython (the system python3) imports it.
#
# Where ParaView looks (Debian 12's 5.11, checked with strace): paraview, pvpython and
# pvbatch read `<exe dir>/paraview.conf` (here /usr/bin/paraview.conf), a list of plugin
# configuration XML files; Debian's paraview does not ship one, so its own
# paraview.plugins.xml is never read and nothing is listed under Tools > Manage Plugins.
# Our package ships that file naming only our XML, which lists PiSurfaces (not auto-loaded):
# `paraview --plugins=PiSurfaces`, `LoadDistributedPlugin('PiSurfaces')` and the plugin
# manager find it. If the system's ParaView owns /usr/bin/paraview.conf itself, the
# package stops with an error instead of taking it over.
set -euo pipefail

BUILD="$(cd "$1" && pwd)"
OUT="$(mkdir -p "$2" && cd "$2" && pwd)"
SRC="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

die() { echo "package: $*" >&2; exit 1; }

multiarch="$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || gcc -print-multiarch)"
arch="$(dpkg --print-architecture)"
pv_version="$(dpkg-query -W -f='${Version}' paraview 2>/dev/null)" ||
  die "the system's paraview package is not installed"
pv_series="$(sed -E 's/^ParaView ([0-9]+\.[0-9]+).*/\1/' "$BUILD/pisurfaces-stack.txt")"
plugin_dir="/usr/lib/$multiarch/paraview-$pv_series/plugins"
[ -d "$plugin_dir" ] || die "$plugin_dir does not exist: is this build for the system's ParaView ($(cat "$BUILD/pisurfaces-stack.txt"))?"
# Debian 13's paraview ships its own paraview.conf in its library directory, read in a way
# not examined yet: the package is made for Debian 12's layout only, for now.
if [ -e "/usr/lib/$multiarch/paraview-$pv_series/paraview.conf" ]; then
  die "this ParaView ($pv_series) reads /usr/lib/$multiarch/paraview-$pv_series/paraview.conf; packaging for it is not supported yet (Debian 12's 5.11 is)"
fi
if dpkg -S /usr/bin/paraview.conf >/dev/null 2>&1 &&
   ! dpkg -S /usr/bin/paraview.conf | grep -q '^pisurfaces:'; then
  die "/usr/bin/paraview.conf belongs to $(dpkg -S /usr/bin/paraview.conf | cut -d: -f1); not taking it over"
fi
version="$(sed -nE 's/^project\(PiSurfaces VERSION ([0-9.]+).*/\1/p' "$SRC/CMakeLists.txt")"
codename="$(. /etc/os-release && echo "$VERSION_CODENAME")"
deb_version="$version-1~${codename}"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cmake --install "$BUILD" --prefix "$work/install" >/dev/null

stage="$work/stage"
mkdir -p "$stage$plugin_dir/PiSurfaces" "$stage/usr/lib/$multiarch" \
  "$stage/usr/lib/python3/dist-packages/pisurfaces" "$stage/usr/bin" "$stage/DEBIAN" \
  "$stage/usr/share/doc/pisurfaces"
# The plugin with its own module's library beside it (found through the plugin's
# RUNPATH $ORIGIN), and the libraries of our VTK modules (sonames in the linker's path).
cp "$work/install/lib/paraview-plugins/PiSurfaces/"*.so "$stage$plugin_dir/PiSurfaces/"
cp -P "$work/install/lib/"libvtkPiSurfaces*.so.* "$stage/usr/lib/$multiarch/"
cat >"$stage$plugin_dir/PiSurfaces/PiSurfaces.plugins.xml" <<XML
<?xml version="1.0"?>
<Plugins>
  <Plugin name="PiSurfaces" filename="PiSurfaces.so" auto_load="0"/>
</Plugins>
XML
echo "$plugin_dir/PiSurfaces/PiSurfaces.plugins.xml" >"$stage/usr/bin/paraview.conf"
# The Python package: the wrapped modules and our __init__.py.
cp "$work/install/lib/python/pisurfaces/"*.so "$stage/usr/lib/python3/dist-packages/pisurfaces/"
cp "$SRC/Python/pisurfaces/__init__.py" "$stage/usr/lib/python3/dist-packages/pisurfaces/"
find "$stage" -name '*.so*' -type f -exec strip --strip-unneeded {} +
find "$stage" -type d -exec chmod 755 {} +
find "$stage" -type f -exec chmod 644 {} +
chmod 644 "$stage/usr/bin/paraview.conf"
cp "$SRC/README.md" "$stage/usr/share/doc/pisurfaces/README.md"

# Library dependencies from the ELF files (dpkg-shlibdeps needs a debian/control).
mkdir -p "$work/shlibs/debian"
printf 'Source: pisurfaces\n\nPackage: pisurfaces\nArchitecture: any\n' >"$work/shlibs/debian/control"
mapfile -t elves < <(find "$stage" -name '*.so*' -type f)
shlibs="$(cd "$work/shlibs" && dpkg-shlibdeps -O -l"$stage/usr/lib/$multiarch" -l"$stage$plugin_dir/PiSurfaces" "${elves[@]}" 2>/dev/null |
  sed -n 's/^shlibs:Depends=//p')"
# A plugin loads only into the ParaView it was built against: pin the exact version.
depends="paraview (= $pv_version), python3-paraview (= $pv_version)${shlibs:+, $shlibs}"

cat >"$stage/DEBIAN/control" <<CONTROL
Package: pisurfaces
Version: $deb_version
Architecture: $arch
Maintainer: PiSurfaces developers <pisurfaces@localhost>
Depends: $depends
Section: science
Priority: optional
Installed-Size: $(du -sk "$stage" | cut -f1)
Description: products of implicit surfaces (Pi-surfaces) for ParaView
 The PiSurfaces plugin for Debian's ParaView $pv_series (Tools > Manage Plugins,
 paraview --plugins=PiSurfaces, LoadDistributedPlugin('PiSurfaces')) and the
 pisurfaces Python package for pvpython.
CONTROL
# pvpython writes __pycache__ into the package's folder: removed with the package.
cat >"$stage/DEBIAN/prerm" <<'PRERM'
#!/bin/sh
set -e
rm -rf /usr/lib/python3/dist-packages/pisurfaces/__pycache__
PRERM
chmod 755 "$stage/DEBIAN/prerm"
# The libraries in the multiarch directory: ld.so's cache is refreshed on install/removal.
echo "activate-noawait ldconfig" >"$stage/DEBIAN/triggers"
deb="$OUT/pisurfaces_${deb_version}_$arch.deb"
dpkg-deb --root-owner-group --build "$stage" "$deb" >/dev/null
echo "$deb"
