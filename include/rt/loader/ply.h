// Our own PLY reader (the assignment names RPly, which is not packaged here).
// Supports ascii, binary_little_endian and binary_big_endian; any vertex property
// layout (x, y, z are picked out, everything else is skipped); face lists whose
// count type is any integer type (uchar/uint8, ushort, int/int32, uint/uint32, ...)
// and whose index type is any integer type; the face property may be called
// vertex_indices or vertex_index; polygons are fan-split into triangles.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rt/core/math.h"

namespace rt {

struct PlyMesh {
    // One per vertex, in the renderer's precision (Real), so the scene loader takes
    // the vector as it is: at 16M triangles a copy was 192 MB of fresh pages.
    // Coordinates are checked finite in the file's own type before conversion.
    std::vector<Vec3> positions;
    std::vector<uint32_t> indices;  // 3 per triangle, 0-based into positions
    size_t polygons_split = 0;      // faces with more than 3 vertices that were fan-split
};

// Throws rt::InputError "<path>: byte <offset>: <what>" (or "<path>: line <n>: <what>"
// for ascii bodies) for a missing file, bad header, truncated body, index out of range,
// faces with fewer than 3 vertices, non-finite coordinates, or counts the file cannot hold.
PlyMesh read_ply(const std::string& path);

// Parses PLY bytes held in memory (the same reader as read_ply); `path` names the
// data in messages. Used by the fuzz target and by tests.
PlyMesh parse_ply(const char* data, size_t size, const std::string& path);

}  // namespace rt
