#!/bin/sh
# Checks the submission tarball (make dist): it extracts into a fresh folder, builds
# there with nothing but g++ and make, and renders. Usage: check_dist.sh raytracer.tar.gz
#
# When run as root with unshare(1) available, the build runs in a private mount
# namespace in which the Debian headers and libraries this project uses
# (nlohmann-json3-dev, libcli11-dev, libstb-dev, libdeflate-dev, libpugixml-dev, libtinyobjloader-dev,
# libgtest-dev) are hidden, as on a machine with only g++. Otherwise it builds with
# RT_HAVE_PUGIXML= RT_HAVE_TINYOBJ= RT_HAVE_LIBDEFLATE= and relies on the checks below: the compile lines
# use -Ithird_party, nothing links libstb/libdeflate/pugixml/tinyobjloader, and no dependency file
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
        nlohmann|CLI|stb|libdeflate.h|pugixml.hpp|pugiconfig.hpp|tiny_obj_loader.h|gtest|gmock) continue ;;
    esac
    ln -s "$f" "$work/include_farm/$(basename "$f")"
done
mount --bind "$work/include_farm" /usr/include
: >"$work/empty"
for lib in /usr/lib/*/libstb.* /usr/lib/*/libdeflate.* /usr/lib/*/libpugixml.* /usr/lib/*/libtinyobjloader* /usr/lib/*/libgtest*; do
    [ -e "$lib" ] && mount --bind "$work/empty" "$lib"
done
cd "$work/src"
[ ! -e /usr/include/nlohmann ] && [ ! -e /usr/include/CLI ] && [ ! -e /usr/include/stb ] && [ ! -e /usr/include/libdeflate.h ] && [ ! -e /usr/include/pugixml.hpp ] || { echo "hiding failed"; exit 1; }
make -j"$(nproc)" >"$work/build.log" 2>&1
HIDE
    unshare -m sh "$work/hide.sh" "$work" || { tail -30 "$work/build.log" 2>/dev/null; fail "make failed with the packaged headers hidden"; }
else
    make -j"$(nproc)" RT_HAVE_PUGIXML= RT_HAVE_TINYOBJ= RT_HAVE_LIBDEFLATE= >"$work/build.log" 2>&1 || { tail -30 "$work/build.log"; fail "make failed"; }
fi

grep -q -- '-Ithird_party' "$work/build.log" || fail "the build did not use -Ithird_party"
grep -q 'stb_impl' "$work/build.log" || fail "src/image/stb_impl.cpp was not compiled"
grep -q -- '-DRT_NO_LIBDEFLATE' "$work/build.log" || fail "the build did not fall back to stb's compressor (-DRT_NO_LIBDEFLATE)"
if grep -E -- '-l(stb|deflate|pugixml|tinyobjloader)' "$work/build.log"; then fail "the build links a packaged library"; fi
[ -x raytracer ] || fail "no ./raytracer"
[ ! -e rtconvert ] || fail "./rtconvert was built without pugixml and tinyobjloader"
if find build -name '*.d' -exec cat {} + | grep -E '/usr/include/(nlohmann|CLI|stb|libdeflate|pugixml|tiny_obj)'; then
    fail "a dependency file names a packaged header"
fi
if ldd ./raytracer | grep -E 'libstb|libdeflate|pugixml|tinyobj'; then fail "./raytracer needs a packaged library"; fi

./raytracer scenes/showcase.json >"$work/run.log" 2>&1 || { cat "$work/run.log"; fail "./raytracer scenes/showcase.json failed"; }
[ -s showcase.png ] || fail "no showcase.png"
if [ -x "$repo/raytracer" ]; then
    # The same renderer built the Debian way must give the same pixels. Not the same
    # bytes: there libdeflate compresses the PNG, here stb does (mk/png.mk). Both are
    # decoded with the tarball's stb_image.
    "$repo/raytracer" -q -o "$work/ref" scenes/showcase.json
    cat >"$work/pngsame.cpp" <<'CPP'
// pngsame a.png b.png: exit 0 when both decode to the same size and 8-bit RGB pixels.
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
#include <cstring>
int main(int argc, char** argv) {
    if (argc != 3) return 2;
    int w[2], h[2], n[2];
    unsigned char* p[2];
    for (int i = 0; i < 2; ++i)
        if (!(p[i] = stbi_load(argv[i + 1], &w[i], &h[i], &n[i], 3))) return 2;
    return w[0] == w[1] && h[0] == h[1] && std::memcmp(p[0], p[1], size_t(w[0]) * size_t(h[0]) * 3) == 0 ? 0 : 1;
}
CPP
    g++ -O1 -w -Ithird_party -o "$work/pngsame" "$work/pngsame.cpp" || fail "cannot build the PNG comparer"
    "$work/pngsame" showcase.png "$work/ref/showcase.png" || fail "showcase.png's pixels differ from the repository build's"
fi
printf '<Scene></Scene>\n' >"$work/s.xml"
if ./raytracer "$work/s.xml" >"$work/xml.log" 2>&1; then fail "an XML scene was accepted without pugixml"; fi
grep -q 'not supported by this build' "$work/xml.log" || { cat "$work/xml.log"; fail "no clear message for XML"; }

echo "dist-check: OK ($(basename "$tarball"): built with only g++ and the tarball's third_party/ (packaged headers and libraries hidden: $hidden); -Ithird_party, stb_impl.cpp, RT_NO_LIBDEFLATE, no -lstb/-ldeflate/-lpugixml/-ltinyobjloader, no rtconvert; showcase.png rendered (stb's compressor), its pixels identical to the repository build's; XML refused with a clear message)"
