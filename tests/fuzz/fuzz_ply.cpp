// libFuzzer target for the PLY reader: the input is a whole PLY file in memory.
// Any outcome but a PlyMesh or an rt::InputError is a finding (a crash, a
// sanitizer report, a hang, an allocation beyond -rss_limit_mb). The result is
// checked against the reader's contract too: indices in range, three per triangle,
// finite coordinates.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "rt/core/error.h"
#include "rt/loader/ply.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        const rt::PlyMesh m = rt::parse_ply(reinterpret_cast<const char*>(data), size, "fuzz.ply");
        if (m.indices.size() % 3 != 0) std::abort();
        const size_t nv = m.positions.size();
        for (uint32_t i : m.indices)
            if (i >= nv) std::abort();
        for (const rt::Vec3& p : m.positions)
            if (!rt::isfinite(p)) std::abort();
    } catch (const rt::InputError&) {
        // The expected answer to bad input.
    }
    return 0;
}
