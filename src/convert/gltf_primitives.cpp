// glTF triangle primitives (gltf_primitives.h, docs/gltf.md).
#include "gltf_primitives.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "rt/core/error.h"
#include "rt/loader/scene_desc.h"

namespace rt {
#ifndef RT_NO_GLTF
namespace {

using json = nlohmann::json;
using V3 = std::array<double, 3>;

// Whether every corner's normal is its triangle's own: a flat-shaded mesh as modelling
// tools write it (vertices split where faces meet), drawn flat (docs/gltf.md).
bool flat_normals(const GltfTriangles& g, const std::vector<double>& normals) {
    if (normals.size() != g.positions.size()) return false;
    auto at = [](const std::vector<double>& v, uint32_t i) { return V3{v[3 * i], v[3 * i + 1], v[3 * i + 2]}; };
    for (size_t t = 0; t + 2 < g.indices.size(); t += 3) {
        const V3 a = at(g.positions, g.indices[t]), e1 = sub(at(g.positions, g.indices[t + 1]), a),
                 e2 = sub(at(g.positions, g.indices[t + 2]), a);
        const V3 n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        const double len = norm(n);
        if (!(len > 0)) continue;  // degenerate: no normal of its own
        for (size_t k = 0; k < 3; ++k) {
            const V3 c = at(normals, g.indices[t + k]);
            const double cl = norm(c);
            if (!(cl > 0) || (c[0] * n[0] + c[1] * n[1] + c[2] * n[2]) / (cl * len) < 1 - 1e-6) return false;
        }
    }
    return true;
}

// Joins vertices at the same place whose normals agree to 1e-6 (under 0.08 degrees):
// glTF writers split a vertex wherever some attribute differs (texture seams, the
// rounding of stored normals), which the course's smooth shading, averaging over the
// faces that share a vertex, would show as seams. Creases, where normals differ, stay.
void weld(GltfTriangles& g, const std::vector<double>& normals) {
    if (normals.size() != g.positions.size()) return;
    std::map<std::array<double, 3>, std::vector<uint32_t>> at;  // position -> kept vertices there
    std::vector<uint32_t> kept_as(g.positions.size() / 3);
    std::vector<double> positions, kept_normals;
    for (size_t i = 0; i < kept_as.size(); ++i) {
        const V3 p{g.positions[3 * i], g.positions[3 * i + 1], g.positions[3 * i + 2]};
        const V3 n{normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]};
        const double nl = norm(n);
        std::vector<uint32_t>& here = at[p];
        bool found = false;
        for (uint32_t k : here) {
            const double* q = &kept_normals[3 * size_t(k)];
            const double ql = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
            if (nl > 0 && ql > 0 && (n[0] * q[0] + n[1] * q[1] + n[2] * q[2]) / (nl * ql) >= 1 - 1e-6) {
                kept_as[i] = k;
                found = true;
                break;
            }
        }
        if (found) continue;
        kept_as[i] = uint32_t(positions.size() / 3);
        here.push_back(kept_as[i]);
        positions.insert(positions.end(), p.begin(), p.end());
        kept_normals.insert(kept_normals.end(), n.begin(), n.end());
    }
    for (uint32_t& index : g.indices) index = kept_as[index];
    g.positions = std::move(positions);
}

}  // namespace

std::vector<GltfTriangles> split_triangles(const GltfTriangles& g, const std::vector<uint32_t>& group, size_t groups) {
    std::vector<GltfTriangles> parts(groups);
    std::vector<uint32_t> local(g.positions.size() / 3);
    std::vector<uint32_t> owner(local.size(), UINT32_MAX);  // the group whose `local` numbers vertex v
    for (GltfTriangles& part : parts) part.smooth = g.smooth;
    for (size_t t = 0; t + 2 < g.indices.size(); t += 3) {
        const uint32_t p = group[t / 3];
        GltfTriangles& part = parts[p];
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t v = g.indices[t + k];
            if (owner[v] != p) {
                owner[v] = p;
                local[v] = uint32_t(part.positions.size() / 3);
                for (size_t a = 0; a < 3; ++a) {
                    const double x = g.positions[3 * v + a];
                    part.positions.push_back(x);
                    part.lo[a] = std::min(part.lo[a], x);
                    part.hi[a] = std::max(part.hi[a], x);
                }
            }
            part.indices.push_back(local[v]);
        }
    }
    return parts;
}

std::vector<GltfTriangles> connected_parts(const GltfTriangles& g) {
    size_t parts = 0;
    const std::vector<uint32_t> group = part_of_triangles(g, parts);
    return split_triangles(g, group, parts);
}

std::vector<uint32_t> part_of_triangles(const GltfTriangles& g, size_t& parts) {
    const size_t n = g.positions.size() / 3;
    std::vector<uint32_t> root(n);
    for (size_t i = 0; i < n; ++i) root[i] = uint32_t(i);
    auto find = [&](uint32_t v) {
        while (root[v] != v) v = root[v] = root[root[v]];
        return v;
    };
    for (size_t t = 0; t + 2 < g.indices.size(); t += 3)
        for (size_t k = 1; k < 3; ++k) root[find(g.indices[t + k])] = find(g.indices[t]);
    std::vector<uint32_t> part_of_root(n, UINT32_MAX), group;
    parts = 0;
    for (size_t t = 0; t + 2 < g.indices.size(); t += 3) {
        uint32_t& p = part_of_root[find(g.indices[t])];
        if (p == UINT32_MAX) p = uint32_t(parts++);
        group.push_back(p);
    }
    return group;
}

void GltfPrimitives::fail(const std::string& element, const std::string& what) const {
    throw InputError(path_ + ": " + element + ": " + what);
}

// Element k's bytes of accessor `index`, each range checked; `where` names its user.
GltfPrimitives::View GltfPrimitives::view(int index, int component, int type, const std::string& where) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
        fail(where, "accessor " + std::to_string(index) + " does not exist (the file has " +
                        std::to_string(model_.accessors.size()) + ")");
    const tinygltf::Accessor& a = model_.accessors[size_t(index)];
    const std::string ap = "/accessors/" + std::to_string(index);
    if (a.sparse.isSparse) fail(ap, "sparse accessors are not read");
    if (a.type != type) fail(ap, "has the wrong type for " + where);
    if (component >= 0 && a.componentType != component)
        fail(ap, "has component type " + std::to_string(a.componentType) + " (" + where + " needs floats)");
    View v;
    v.count = a.count;
    if (a.bufferView < 0) return v;
    if (size_t(a.bufferView) >= model_.bufferViews.size())
        fail(ap, "bufferView " + std::to_string(a.bufferView) + " does not exist");
    const tinygltf::BufferView& bv = model_.bufferViews[size_t(a.bufferView)];
    const std::string vp = "/bufferViews/" + std::to_string(a.bufferView);
    if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size())
        fail(vp, "buffer " + std::to_string(bv.buffer) + " does not exist");
    const std::vector<unsigned char>& buf = model_.buffers[size_t(bv.buffer)].data;
    const int elem = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType)) *
                     tinygltf::GetNumComponentsInType(uint32_t(a.type));
    if (elem <= 0) fail(ap, "unknown component type " + std::to_string(a.componentType));
    v.stride = bv.byteStride ? bv.byteStride : size_t(elem);
    if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset)
        fail(vp, "runs past the end of buffer " + std::to_string(bv.buffer) + " (" + std::to_string(buf.size()) +
                     " bytes)");
    if (a.count > 0 && (a.byteOffset > bv.byteLength || (a.count - 1) > (bv.byteLength - a.byteOffset) / v.stride ||
                        a.byteOffset + (a.count - 1) * v.stride + size_t(elem) > bv.byteLength))
        fail(ap, "runs past the end of its bufferView (" + std::to_string(bv.byteLength) + " bytes)");
    v.data = buf.data() + bv.byteOffset + a.byteOffset;
    return v;
}

std::vector<double> GltfPrimitives::numbers(int index, int type, const std::string& where) const {
    const View v = view(index, -1, type, where);
    const tinygltf::Accessor& a = model_.accessors[size_t(index)];
    const std::string ap = "/accessors/" + std::to_string(index);
    // Floats, or KHR_mesh_quantization's integers: normalised (to [0, 1], or [-1, 1] with
    // the most negative value -1 too), or taken as they are.
    const std::map<int, double> largest = {{TINYGLTF_COMPONENT_TYPE_FLOAT, 0},
                                           {TINYGLTF_COMPONENT_TYPE_BYTE, 127},
                                           {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, 255},
                                           {TINYGLTF_COMPONENT_TYPE_SHORT, 32767},
                                           {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 65535}};
    const auto kind = largest.find(a.componentType);
    if (kind == largest.end())
        fail(ap, "has component type " + std::to_string(a.componentType) + " (" + where +
                     " needs floats, or the integers of KHR_mesh_quantization)");
    const double scale = a.normalized && kind->second > 0 ? 1 / kind->second : 1;
    const size_t n = size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
    std::vector<double> out(n * v.count, 0.0);
    if (!v.data) return out;
    for (size_t i = 0; i < v.count; ++i)
        for (size_t k = 0; k < n; ++k) {
            const unsigned char* p = v.data + i * v.stride;
            double x = 0;
            switch (a.componentType) {
                case TINYGLTF_COMPONENT_TYPE_FLOAT: {
                    float f;
                    std::memcpy(&f, p + 4 * k, 4);
                    x = f;
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_BYTE:
                    x = std::max(int8_t(p[k]) * scale, a.normalized ? -1.0 : -128.0);
                    break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                    x = p[k] * scale;
                    break;
                case TINYGLTF_COMPONENT_TYPE_SHORT: {
                    int16_t s;
                    std::memcpy(&s, p + 2 * k, 2);
                    x = std::max(s * scale, a.normalized ? -1.0 : -32768.0);
                    break;
                }
                default: {  // unsigned short
                    uint16_t s;
                    std::memcpy(&s, p + 2 * k, 2);
                    x = s * scale;
                }
            }
            if (!(std::fabs(x) <= kMaxMagnitude))  // the loader's bound (rt/loader/scene_desc.h)
                fail(ap, "element " + std::to_string(i) + " is not a finite number within +-1e30");
            out[n * i + k] = x;
        }
    return out;
}

std::vector<uint32_t> GltfPrimitives::indices(int index, size_t vertices, const std::string& where) const {
    const tinygltf::Accessor* a =
        index >= 0 && size_t(index) < model_.accessors.size() ? &model_.accessors[size_t(index)] : nullptr;
    const int component = a ? a->componentType : -1;
    if (a && component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail("/accessors/" + std::to_string(index), "indices must be unsigned integers");
    const View v = view(index, component, TINYGLTF_TYPE_SCALAR, where + "/indices");
    std::vector<uint32_t> out(v.count, 0);
    for (size_t i = 0; v.data && i < v.count; ++i) {
        const unsigned char* p = v.data + i * v.stride;
        uint32_t x = 0;
        if (component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
            x = p[0];
        } else if (component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            uint16_t s;
            std::memcpy(&s, p, 2);
            x = s;
        } else {
            std::memcpy(&x, p, 4);
        }
        if (x >= vertices)
            fail(where, "index " + std::to_string(x) + " (element " + std::to_string(i) +
                            ") is out of range: POSITION has " + std::to_string(vertices) + " vertices");
        out[i] = x;
    }
    return out;
}

std::vector<uint32_t> GltfPrimitives::corners(int m, int p) const {
    const tinygltf::Primitive& prim = model_.meshes[size_t(m)].primitives[size_t(p)];
    const std::string where = "/meshes/" + std::to_string(m) + "/primitives/" + std::to_string(p);
    const int pos = prim.attributes.at("POSITION");
    const size_t n = view(pos, -1, TINYGLTF_TYPE_VEC3, where + "/attributes/POSITION").count;
    std::vector<uint32_t> out;
    if (prim.indices >= 0) {
        out = indices(prim.indices, n, where);
    } else {
        for (uint32_t i = 0; i < n; ++i) out.push_back(i);
    }
    out.resize(out.size() - out.size() % 3);
    return out;
}

const GltfTriangles* GltfPrimitives::get(int m, int p) {
    const tinygltf::Primitive& prim = model_.meshes[size_t(m)].primitives[size_t(p)];
    const std::string where = "/meshes/" + std::to_string(m) + "/primitives/" + std::to_string(p);
    if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) {
        if (skipped_.insert(where).second)
            warn(where + ": mode " + std::to_string(prim.mode) +
                 " (points, lines or strips) is not a triangle list: skipped");
        return nullptr;
    }
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) {
        if (skipped_.insert(where).second) warn(where + ": no POSITION: skipped");
        return nullptr;
    }
    const auto key = std::make_pair(pos->second, prim.indices);
    if (const auto it = read_.find(key); it != read_.end()) return &it->second;
    GltfTriangles g;
    g.positions = numbers(pos->second, TINYGLTF_TYPE_VEC3, where + "/attributes/POSITION");
    const size_t n = g.positions.size() / 3;
    g.indices = corners(m, p);
    if (const size_t all = prim.indices >= 0 ? model_.accessors[size_t(prim.indices)].count : n; all % 3)
        warn(where + ": " + std::to_string(all) + " indices, not a multiple of 3: the last " + std::to_string(all % 3) +
             " left out");
    const json extras = ours_in(model_.meshes[size_t(m)].extras);
    if (const auto nrm = prim.attributes.find("NORMAL"); nrm != prim.attributes.end()) {
        const std::vector<double> normals = numbers(nrm->second, TINYGLTF_TYPE_VEC3, where + "/attributes/NORMAL");
        g.smooth = !flat_normals(g, normals);
        // Vertices as the export wrote them need no welding; other tools split them.
        const bool as_exported = extras.is_object() && extras.value("vertices", json()) == json(n);
        if (g.smooth && !as_exported) weld(g, normals);
    }
    // Positions a float could not hold, kept by the export: used while they round to these.
    if (extras.is_object() && extras.contains("positions")) {
        const json& exact = extras["positions"];
        bool same = exact.is_array() && exact.size() == g.positions.size();
        for (size_t i = 0; same && i < g.positions.size(); ++i)
            same = exact[i].is_number() && double(float(exact[i].get<double>())) == g.positions[i];
        if (same)
            for (size_t i = 0; i < g.positions.size(); ++i) g.positions[i] = exact[i].get<double>();
    }
    for (size_t i = 0; i < g.positions.size(); ++i) {
        g.lo[i % 3] = std::min(g.lo[i % 3], g.positions[i]);
        g.hi[i % 3] = std::max(g.hi[i % 3], g.positions[i]);
    }
    return &read_.emplace(key, std::move(g)).first->second;
}
#endif  // RT_NO_GLTF

}  // namespace rt
