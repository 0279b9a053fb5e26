#!/bin/sh
# Checks the submission tarball (make dist): it extracts into a fresh folder, builds
# there with nothing but g++ and make, and renders. Usage: check_dist.sh raytracer.tar.gz
#
# When run as root with unshare(1) available, the build runs in a private mount
# namespace in which the Debian headers and libraries this project uses
# (nlohmann-json3-dev, libcli11-dev, libstb-dev, libpugixml-dev, libtinyobjloader-dev, libgtest-dev)
# are hidden, as on a machine with only g++. Otherwise it builds with
# RT_HAVE_PUGIXML= RT_HAVE_TINYOBJ= and relies on the checks below: the compile lines
# use -Ithird_party, nothing links libstb/pugixml/tinyobjloader, and no dependency file
# names a header outside the tarball but the C/C++ runtime's.
set -eu
tarball=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
repo=$(pwd)
work=$(mktemp -d /tmp/rt_dist_XXXXXX)
trap 'rm -rf "$work"' EXIT INT TERM
fail() { echo "dist-check: FAIL: $*" >&2; exit 1; }

mkdir "$work/src"
tar -xf "$tarball" -C "$work/src"
cd "$work/src"
for f in Makefile README.md src/main.cpp src/image/stb_impl.cpp include/rt/render.h scenes/showcase.json \
         third_party/nlohmann/json.hpp third_party/CLI/CLI.hpp third_party/stb/stb_image_write.h third_party/stb/stb_image.h; do
    [ -f "$f" ] || fail "the tarball lacks $f"
done
[ ! -e build ] && [ ! -e raytracer ] || fail "the tarball holds build products"

build_plain() {
    make -j"$(nproc)" >"$work/build.log" 2>&1 || { tail -30 "$work/build.log"; fail "make failed"; }
}

hidden=no
if [ "$(id -u)" = 0 ] && command -v unshare >/dev/null 2>&1 && unshare -m true 2>/dev/null; then
    hidden=yes
    # /usr/include becomes a folder of links to the real one, minus the packaged headers;
    # the packaged libraries are replaced by empty files (a link against one fails).
    cat >"$work/hide.sh" <<'HIDE'
set -eu
work=$1
mkdir -p "$work/orig_include" "$work/include_farm"
mount --bind /usr/include "$work/orig_include"
for f in "$work"/orig_include/* "$work"/orig_include/.[!.]*; do
    [ -e "$f" ] || continue
    case "$(basename "$f")" in
        nlohmann|CLI|stb|pugixml.hpp|pugiconfig.hpp|tiny_obj_loader.h|gtest|gmock) continue ;;
    esac
    ln -s "$f" "$work/include_farm/$(basename "$f")"
done
mount --bind "$work/include_farm" /usr/include
: >"$work/empty"
for lib in /usr/lib/*/libstb.* /usr/lib/*/libpugixml.* /usr/lib/*/libtinyobjloader* /usr/lib/*/libgtest*; do
    [ -e "$lib" ] && mount --bind "$work/empty" "$lib"
done
cd "$work/src"
[ ! -e /usr/include/nlohmann ] && [ ! -e /usr/include/CLI ] && [ ! -e /usr/include/stb ] && [ ! -e /usr/include/pugixml.hpp ] || { echo "hiding failed"; exit 1; }
make -j"$(nproc)" >"$work/build.log" 2>&1
HIDE
    unshare -m sh "$work/hide.sh" "$work" || { tail -30 "$work/build.log" 2>/dev/null; fail "make failed with the packaged headers hidden"; }
else
    make -j"$(nproc)" RT_HAVE_PUGIXML= RT_HAVE_TINYOBJ= >"$work/build.log" 2>&1 || { tail -30 "$work/build.log"; fail "make failed"; }
fi

grep -q -- '-Ithird_party' "$work/build.log" || fail "the build did not use -Ithird_party"
grep -q 'stb_impl' "$work/build.log" || fail "src/image/stb_impl.cpp was not compiled"
if grep -E -- '-l(stb|pugixml|tinyobjloader)' "$work/build.log"; then fail "the build links a packaged library"; fi
[ -x raytracer ] || fail "no ./raytracer"
[ ! -e rtconvert ] || fail "./rtconvert was built without pugixml and tinyobjloader"
if find build -name '*.d' -exec cat {} + | grep -E '/usr/include/(nlohmann|CLI|stb|pugixml|tiny_obj)'; then
    fail "a dependency file names a packaged header"
fi
if ldd ./raytracer | grep -E 'libstb|pugixml|tinyobj'; then fail "./raytracer needs a packaged library"; fi

./raytracer scenes/showcase.json >"$work/run.log" 2>&1 || { cat "$work/run.log"; fail "./raytracer scenes/showcase.json failed"; }
[ -s showcase.png ] || fail "no showcase.png"
if [ -x "$repo/raytracer" ]; then
    # The same renderer built the Debian way must give the same PNG, byte for byte.
    "$repo/raytracer" -q -o "$work/ref" scenes/showcase.json
    cmp -s showcase.png "$work/ref/showcase.png" || fail "showcase.png differs from the repository build's"
fi
printf '<Scene></Scene>\n' >"$work/s.xml"
if ./raytracer "$work/s.xml" >"$work/xml.log" 2>&1; then fail "an XML scene was accepted without pugixml"; fi
grep -q 'not supported by this build' "$work/xml.log" || { cat "$work/xml.log"; fail "no clear message for XML"; }

echo "dist-check: OK ($(basename "$tarball"): built with only g++ and the tarball's third_party/ (packaged headers and libraries hidden: $hidden); -Ithird_party, stb_impl.cpp, no -lstb/-lpugixml/-ltinyobjloader, no rtconvert; showcase.png rendered, identical to the repository build's; XML refused with a clear message)"
