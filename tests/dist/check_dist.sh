#!/bin/sh
# Checks the submission tarball (make dist): it extracts into a fresh folder, builds
# there with nothing but g++ and make, and renders. Usage: check_dist.sh raytracer.tar.gz
#
# The build is plain `make` (no -j), as a grader runs it, and is timed: above
# DIST_BUILD_LIMIT seconds of wall time (default 180, docs/dist.md) the check fails. It must
# build ./raytracer alone, in double precision; the float opt-in (make PRECISIONS="double
# float") is then built with -j and checked too, untimed.
#
# When run as root with unshare(1) available, the build runs in a private mount
# namespace in which the Debian headers and libraries this project uses
# (nlohmann-json3-dev, libcli11-dev, libstb-dev, libdeflate-dev, libpugixml-dev, libtinyobjloader-dev,
# libmeshoptimizer-dev, libdraco-dev, libgtest-dev) are hidden, as on a machine with only g++. Otherwise it builds with
# RT_HAVE_PUGIXML= RT_HAVE_TINYOBJ= RT_HAVE_LIBDEFLATE= and relies on the checks below: the compile lines
# use -Ithird_party, nothing links libstb/libdeflate/pugixml/tinyobjloader, and no dependency file
# names a header outside the tarball but the C/C++ runtime's.
set -eu
tarball=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
repo=$(pwd)
work=$(mktemp -d -t rt_dist_XXXXXX)
trap 'rm -rf "$work"' EXIT INT TERM
fail() { echo "dist-check: FAIL: $*" >&2; exit 1; }

mkdir "$work/src"
tar -xf "$tarball" -C "$work/src"
cd "$work/src"
for f in Makefile README.md src/main.cpp src/image/stb_impl.cpp include/rt/render/render.h scenes/showcase.json \
         third_party/nlohmann/json.hpp third_party/CLI/CLI.hpp third_party/stb/stb_image_write.h third_party/stb/stb_image.h; do
    [ -f "$f" ] || fail "the tarball lacks $f"
done
[ ! -e build ] && [ ! -e raytracer ] || fail "the tarball holds build products"

limit=${DIST_BUILD_LIMIT:-180}

# timed.sh LOG COMMAND...: runs COMMAND, its output to LOG, and writes its wall, user and
# sys seconds to LOG.time.
cat >"$work/timed.sh" <<'TIMED'
log=$1; shift
start=$(date +%s.%N)
if [ -x /usr/bin/time ]; then
    /usr/bin/time -f '%U %S' -o "$log.cpu" "$@" >"$log" 2>&1; rc=$?
else
    "$@" >"$log" 2>&1; rc=$?; echo '? ?' >"$log.cpu"
fi
echo "$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') $(cat "$log.cpu")" >"$log.time"
exit $rc
TIMED

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
        nlohmann|CLI|stb|libdeflate.h|pugixml.hpp|pugiconfig.hpp|tiny_obj_loader.h|tiny_gltf.h|meshoptimizer.h|draco|gtest|gmock) continue ;;
    esac
    ln -sfn "$f" "$work/include_farm/$(basename "$f")"
done
mount --bind "$work/include_farm" /usr/include
: >"$work/empty"
for lib in /usr/lib/*/libstb.* /usr/lib/*/libdeflate.* /usr/lib/*/libpugixml.* /usr/lib/*/libtinyobjloader* /usr/lib/*/libtinygltf* /usr/lib/*/libmeshoptimizer* /usr/lib/*/libdraco* /usr/lib/*/libgtest*; do
    [ -e "$lib" ] && mount --bind "$work/empty" "$lib"
done
cd "$work/src"
[ ! -e /usr/include/nlohmann ] && [ ! -e /usr/include/CLI ] && [ ! -e /usr/include/stb ] && [ ! -e /usr/include/libdeflate.h ] && [ ! -e /usr/include/pugixml.hpp ] || { echo "hiding failed"; exit 1; }
shift
sh "$work/timed.sh" "$@"
HIDE
fi
# build LOG [make args...]: make in the tarball's folder as on a machine with only g++.
build() {
    log=$1; shift
    if [ $hidden = yes ]; then
        unshare -m sh "$work/hide.sh" "$work" "$log" make "$@"
    else
        sh "$work/timed.sh" "$log" make RT_HAVE_PUGIXML= RT_HAVE_TINYOBJ= RT_HAVE_LIBDEFLATE= RT_HAVE_MESHOPT= RT_HAVE_DRACO= "$@"
    fi
}

build "$work/build.log" || { tail -30 "$work/build.log" 2>/dev/null; fail "make failed (packaged headers hidden: $hidden)"; }
read -r wall user sys <"$work/build.log.time"
echo "dist-check: plain make of the tarball: $wall s wall, $user s user, $sys s sys (limit $limit s wall)"
awk -v w="$wall" -v l="$limit" 'BEGIN { exit !(w <= l) }' || fail "plain make took $wall s, above DIST_BUILD_LIMIT=$limit s"

grep -q -- '-Ithird_party' "$work/build.log" || fail "the build did not use -Ithird_party"
grep -q 'stb_impl' "$work/build.log" || fail "src/image/stb_impl.cpp was not compiled"
grep -q -- '-DRT_NO_LIBDEFLATE' "$work/build.log" || fail "the build did not fall back to stb's compressor (-DRT_NO_LIBDEFLATE)"
if grep -E -- '-l(stb|deflate|pugixml|tinyobjloader|meshoptimizer|draco)' "$work/build.log"; then fail "the build links a packaged library"; fi
[ -x raytracer ] || fail "no ./raytracer"
[ ! -e rtconvert ] || fail "plain make built ./rtconvert"
[ ! -e rtdiff ] || fail "plain make built ./rtdiff"
if grep -E -- '-DRT_REAL_FLOAT|src/convert/|image_diff\.cpp|diff_page\.cpp' "$work/build.log"; then
    fail "plain make compiled the float copy or code ./raytracer does not link"
fi
if find build -name '*.d' -exec cat {} + | grep -E '/usr/include/(nlohmann|CLI|stb|libdeflate|pugixml|tiny_obj|tiny_gltf)'; then
    fail "a dependency file names a packaged header"
fi
if ldd ./raytracer | grep -E 'libstb|libdeflate|pugixml|tinyobj|meshoptimizer|draco'; then fail "./raytracer needs a packaged library"; fi

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

# Double only: --precision float is a usage error of one line, no crash, no image.
rm -f showcase.png
rc=0; ./raytracer --precision float scenes/showcase.json >"$work/float.log" 2>&1 || rc=$?
[ $rc = 2 ] && [ "$(wc -l <"$work/float.log")" = 1 ] && grep -q '^error: .*this build has no float precision; build it with make' "$work/float.log" ||
    { cat "$work/float.log"; fail "--precision float in the double-only build: exit $rc, not the one-line error with exit 2"; }
[ ! -e showcase.png ] || fail "--precision float in the double-only build wrote an image"

# The documented opt-in adds the float copy to ./raytracer.
build "$work/float-build.log" -j"$(nproc)" PRECISIONS="double float" ||
    { tail -30 "$work/float-build.log"; fail "make PRECISIONS=\"double float\" failed"; }
if grep -- ' -c ' "$work/float-build.log" | grep -v -e '-DRT_REAL_FLOAT' -e 'src/main\.cpp'; then
    fail "make PRECISIONS=\"double float\" compiled the double library again"
fi
./raytracer --precision float -q -o "$work/float" scenes/showcase.json || fail "--precision float failed after the opt-in"
if [ -x "$repo/raytracer" ]; then
    "$repo/raytracer" --precision float -q -o "$work/ref_float" scenes/showcase.json
    "$work/pngsame" "$work/float/showcase.png" "$work/ref_float/showcase.png" ||
        fail "the float showcase.png's pixels differ from the repository build's"
fi

echo "dist-check: OK ($(basename "$tarball"): plain make built ./raytracer alone (double precision, no rtconvert, rtdiff or float copy) in $wall s, within $limit s, with only g++ and the tarball's third_party/ (packaged headers and libraries hidden: $hidden); -Ithird_party, stb_impl.cpp, RT_NO_LIBDEFLATE, no -lstb/-ldeflate/-lpugixml/-ltinyobjloader; showcase.png rendered (stb's compressor), its pixels identical to the repository build's; XML refused with a clear message; --precision float refused with one line (exit 2) and rendered after make PRECISIONS=\"double float\")"
