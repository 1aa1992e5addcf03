#include "render/scene/obj_loader.h"

#include <tiny_obj_loader.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <set>
#include <unordered_map>
#include <vector>

#include "render/scene/obj_check.h"
#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu {

namespace {

// tinyobjloader reports failures as text ending in newlines, with the line as "line N" or "line: N"; the
// number goes into the SourceLocation so the message reads like every other Rimu input error.
[[noreturn]] void throw_tinyobj_error(const std::string& file, std::string message) {
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
  for (char& c : message)
    if (c == '\n') c = ' ';
  int line = 0;
  for (size_t at = message.find("line"); at != std::string::npos && line == 0; at = message.find("line", at + 4)) {
    size_t i = at + 4;
    while (i < message.size() && (message[i] == ' ' || message[i] == ':')) ++i;
    while (i < message.size() && std::isdigit(static_cast<unsigned char>(message[i])) && line < 100'000'000)
      line = 10 * line + (message[i++] - '0');
  }
  throw InputError({file, line, ""}, "tinyobjloader: " + (message.empty() ? "could not parse the file" : message));
}

// One corner of the de-indexed mesh. A corner without a normal in a mesh that has normals gets its triangle's
// geometric normal, so its `normal` field is a per-triangle id (negative) that no file index can equal.
struct CornerKey {
  int position, texcoord, normal;
  bool operator==(const CornerKey&) const = default;
};
struct CornerHash {
  size_t operator()(const CornerKey& k) const {
    const auto h = [](int v) { return std::hash<int>{}(v); };
    return h(k.position) ^ (h(k.texcoord) * 0x9E3779B97F4A7C15ull) ^ (h(k.normal) * 0xC2B2AE3D27D4EB4Full);
  }
};

// The line of statement `index`, or 0 when the check pass and tinyobjloader disagree on the count.
int line_of(const std::vector<int>& lines, size_t expected_count, int index) {
  return lines.size() == expected_count && index >= 0 && static_cast<size_t>(index) < lines.size()
             ? lines[static_cast<size_t>(index)]
             : 0;
}

// Unit normal of triangle (a, b, c), computed in double so large coordinates do not overflow. A degenerate
// triangle has none; it gets +z, any unit vector keeps validate() satisfied, and the scene removes it anyway.
Vec3 geometric_normal(Vec3 a, Vec3 b, Vec3 c) {
  const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
  const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0.0) || !std::isfinite(len)) return {0.0f, 0.0f, 1.0f};
  return {float(n[0] / len), float(n[1] / len), float(n[2] / len)};
}

std::vector<const tinyobj::shape_t*> select_shapes(const std::vector<tinyobj::shape_t>& shapes,
                                                   const std::string& object, const std::string& file) {
  std::vector<const tinyobj::shape_t*> selected;
  for (const tinyobj::shape_t& s : shapes)
    if (!s.mesh.indices.empty() && (object.empty() || s.name == object)) selected.push_back(&s);
  if (!selected.empty()) return selected;
  if (object.empty()) throw InputError({file, 0, ""}, "the file has no faces");
  std::set<std::string> names;
  for (const tinyobj::shape_t& s : shapes)
    if (!s.mesh.indices.empty()) names.insert(s.name.empty() ? "(unnamed)" : "'" + s.name + "'");
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  throw InputError({file, 0, ""}, "no object or group named '" + object +
                                      "' has faces; the file has: " + (known.empty() ? "no faces" : known));
}

}  // namespace

TriangleMesh parse_obj(std::string_view text, const std::string& file, const std::string& object) {
  const obj::StatementLines lines = obj::check_obj_text(text, file);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // Parsing from a string makes tinyobjloader ignore mtllib: Rimu's materials come from the scene file.
  if (!reader.ParseFromString(std::string(text), "", config)) throw_tinyobj_error(file, reader.Error());
  // The remaining warnings are about materials; the ones that mean lost geometry cannot occur after the check.

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const size_t position_count = attrib.vertices.size() / 3, normal_count = attrib.normals.size() / 3;
  const size_t texcoord_count = attrib.texcoords.size() / 2;
  const std::vector<const tinyobj::shape_t*> shapes = select_shapes(reader.GetShapes(), object, file);

  bool has_normals = false, has_uvs = false;
  for (const tinyobj::shape_t* s : shapes)
    for (const tinyobj::index_t& i : s->mesh.indices) {
      has_normals |= i.normal_index >= 0;
      has_uvs |= i.texcoord_index >= 0;
    }

  auto position = [&](int i) {
    if (i < 0 || static_cast<size_t>(i) >= position_count)  // the check pass makes this unreachable
      throw InputError({file, 0, ""}, "a face refers to vertex " + std::to_string(i + 1) + ", which does not exist");
    const Vec3 p{attrib.vertices[3 * size_t(i)], attrib.vertices[3 * size_t(i) + 1],
                 attrib.vertices[3 * size_t(i) + 2]};
    if (!is_finite(p))
      throw InputError({file, line_of(lines.positions, position_count, i), ""}, "the vertex is not finite");
    return p;
  };
  auto normal = [&](int i) {
    if (static_cast<size_t>(i) >= normal_count)
      throw InputError({file, 0, ""}, "a face refers to normal " + std::to_string(i + 1) + ", which does not exist");
    const Vec3 n{attrib.normals[3 * size_t(i)], attrib.normals[3 * size_t(i) + 1], attrib.normals[3 * size_t(i) + 2]};
    const float len = length(n);
    if (!(len > 0.0f) || !std::isfinite(len))
      throw InputError({file, line_of(lines.normals, normal_count, i), ""},
                       "a face uses this normal, which is zero or not finite");
    return n / len;
  };
  auto uv = [&](int i) {
    if (static_cast<size_t>(i) >= texcoord_count)
      throw InputError({file, 0, ""},
                       "a face refers to texture coordinate " + std::to_string(i + 1) + ", which does not exist");
    return Vec2{attrib.texcoords[2 * size_t(i)], attrib.texcoords[2 * size_t(i) + 1]};
  };

  TriangleMesh mesh;
  std::unordered_map<CornerKey, uint32_t, CornerHash> vertex_of;
  int triangle = 0;
  for (const tinyobj::shape_t* s : shapes) {
    const std::vector<tinyobj::index_t>& corners = s->mesh.indices;
    for (size_t t = 0; t + 2 < corners.size(); t += 3, ++triangle) {
      const Vec3 p[3] = {position(corners[t].vertex_index), position(corners[t + 1].vertex_index),
                         position(corners[t + 2].vertex_index)};
      const Vec3 flat = has_normals ? geometric_normal(p[0], p[1], p[2]) : Vec3{};
      for (int k = 0; k < 3; ++k) {
        const tinyobj::index_t& c = corners[t + size_t(k)];
        const CornerKey key{c.vertex_index, has_uvs ? c.texcoord_index : -1,
                            !has_normals ? -1 : (c.normal_index >= 0 ? c.normal_index : -2 - triangle)};
        const auto [it, inserted] = vertex_of.try_emplace(key, static_cast<uint32_t>(mesh.positions.size()));
        if (inserted) {
          mesh.positions.push_back(p[k]);
          if (has_normals) mesh.normals.push_back(c.normal_index >= 0 ? normal(c.normal_index) : flat);
          if (has_uvs) mesh.uvs.push_back(c.texcoord_index >= 0 ? uv(c.texcoord_index) : Vec2{});
        }
        mesh.indices.push_back(it->second);
      }
    }
  }
  return mesh;
}

TriangleMesh load_obj(const std::filesystem::path& path, const std::string& object) {
  return parse_obj(read_input_file(path, kMaxBinaryFileBytes), path.string(), object);
}

}  // namespace rimu
