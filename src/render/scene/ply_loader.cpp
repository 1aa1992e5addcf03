#include "render/scene/ply_loader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

#include "render/scene/gzip_bytes.h"
#include "render/scene/ply_format.h"
#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu {

namespace {

// Where the mesh attributes sit among the vertex element's properties; -1 = absent.
struct VertexLayout {
  std::array<int, 3> position{-1, -1, -1};
  std::array<int, 3> normal{-1, -1, -1};
  std::array<int, 2> uv{-1, -1};
};

// Writers name texture coordinates differently; the first pair present wins.
constexpr std::array<std::array<const char*, 2>, 4> kUvNames = {
    {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}}};

void require_scalar(const ply::Element& vertex, int index, const std::string& file) {
  const ply::Property& p = vertex.properties[static_cast<size_t>(index)];
  if (p.is_list)
    throw InputError({file, p.header_line, ""}, "vertex property '" + p.name + "' must be a scalar, not a list");
}

VertexLayout vertex_layout(const ply::Element& vertex, const std::string& file) {
  VertexLayout layout;
  const char* axes[3] = {"x", "y", "z"};
  const char* normal_axes[3] = {"nx", "ny", "nz"};
  int normals_found = 0;
  for (int i = 0; i < 3; ++i) {
    layout.position[i] = vertex.index_of(axes[i]);
    if (layout.position[i] < 0)
      throw InputError({file, vertex.header_line, ""},
                       std::string("element 'vertex' has no property '") + axes[i] + "'");
    require_scalar(vertex, layout.position[i], file);
    layout.normal[i] = vertex.index_of(normal_axes[i]);
    normals_found += layout.normal[i] >= 0;
  }
  if (normals_found != 0 && normals_found != 3)
    throw InputError({file, vertex.header_line, ""}, "element 'vertex' has some but not all of nx, ny, nz");
  if (normals_found == 0) layout.normal = {-1, -1, -1};
  for (int i = 0; i < 3 && normals_found == 3; ++i) require_scalar(vertex, layout.normal[i], file);
  for (const auto& names : kUvNames) {
    const int u = vertex.index_of(names[0]), v = vertex.index_of(names[1]);
    if (u < 0 || v < 0) continue;
    require_scalar(vertex, u, file);
    require_scalar(vertex, v, file);
    layout.uv = {u, v};
    break;
  }
  return layout;
}

// A double that fits a float without overflow; the cast of a larger one would be undefined behaviour.
bool fits_float(double value) { return std::isfinite(value) && std::fabs(value) <= std::numeric_limits<float>::max(); }

// Reads one record's properties into `values` (lists are skipped: no vertex attribute is a list).
void read_record(ply::BodyReader& reader, const ply::Element& element, std::vector<double>& values) {
  for (size_t p = 0; p < element.properties.size(); ++p) {
    const ply::Property& property = element.properties[p];
    if (property.is_list) {
      const double n = reader.read(property.count_type);
      if (n < 0) reader.fail("list '" + property.name + "' has a negative length");
      reader.skip(property.type, static_cast<uint64_t>(n));
    } else {
      values[p] = reader.read(property.type);
    }
  }
}

// Appends one vertex, `value(i)` being the record's property i; checks what the mesh needs (positions and uvs finite
// in single precision) and fails at `record` otherwise.
template <typename Value>
void append_vertex(ply::BodyReader& reader, const ply::Element& element, uint64_t record, const VertexLayout& layout,
                   Value&& value, TriangleMesh& mesh) {
  const auto fail = [&](const std::string& what) {
    reader.at(element.name, record);
    reader.fail(what);
  };
  const double x = value(layout.position[0]), y = value(layout.position[1]), z = value(layout.position[2]);
  if (!fits_float(x) || !fits_float(y) || !fits_float(z)) {
    std::ostringstream message;
    message << "the position (" << x << ", " << y << ", " << z << ") is not finite in single precision";
    fail(message.str());
  }
  mesh.positions.push_back({static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)});
  if (layout.normal[0] >= 0) {
    // Normals are normalised in double so that large but finite components do not overflow the length.
    const double nx = value(layout.normal[0]), ny = value(layout.normal[1]), nz = value(layout.normal[2]);
    // A zero or non-finite normal (exporters write NaN where a vertex's normal is undefined) is kept as (0, 0, 0),
    // "no normal here": triangles at that vertex are shaded flat, as pbrt-v4 shades them (TriangleMesh::normals).
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (!(len > 0.0) || !std::isfinite(len)) mesh.normals.push_back({0.0f, 0.0f, 0.0f});
    else mesh.normals.push_back({static_cast<float>(nx / len), static_cast<float>(ny / len), static_cast<float>(nz / len)});
  }
  if (layout.uv[0] >= 0) {
    const double u = value(layout.uv[0]), v = value(layout.uv[1]);
    if (!fits_float(u) || !fits_float(v)) fail("the texture coordinate is not finite in single precision");
    mesh.uvs.push_back({static_cast<float>(u), static_cast<float>(v)});
  }
}

void reserve_vertices(uint64_t count, size_t remaining, const VertexLayout& layout, TriangleMesh& mesh) {
  // A record takes at least one byte, so the file size bounds the allocation even when the count is garbage.
  // One spare position: Embree reads the last vertex with a 16-byte load (embree_scene.cpp shares this array).
  const size_t reserve = static_cast<size_t>(std::min<uint64_t>(count, remaining));
  mesh.positions.reserve(reserve + 1);
  if (layout.normal[0] >= 0) mesh.normals.reserve(reserve);
  if (layout.uv[0] >= 0) mesh.uvs.reserve(reserve);
}

// Binary records in this machine's byte order whose properties are all scalars (what exporters write) have one
// size: each attribute is copied out at its offset, without the per-value dispatch of BodyReader::read.
// Returns false (nothing read) for other layouts.
bool read_vertices_native(ply::BodyReader& reader, const ply::Element& element, const VertexLayout& layout,
                          TriangleMesh& mesh) {
  if (!reader.native_order()) return false;
  std::vector<size_t> offsets;
  size_t stride = 0;
  for (const ply::Property& property : element.properties) {
    if (property.is_list) return false;
    offsets.push_back(stride);
    stride += ply::size_of(property.type);
  }
  reserve_vertices(element.count, reader.remaining(), layout, mesh);
  for (uint64_t record = 0; record < element.count; ++record) {
    if (reader.remaining() < stride) reader.at(element.name, record);  // names the record take() fails at
    const char* bytes = reader.take(stride);
    const auto value = [&](int index) {
      return ply::native_value(bytes + offsets[size_t(index)], element.properties[size_t(index)].type);
    };
    append_vertex(reader, element, record, layout, value, mesh);
  }
  return true;
}

void read_vertices(ply::BodyReader& reader, const ply::Element& element, const VertexLayout& layout,
                   TriangleMesh& mesh) {
  if (read_vertices_native(reader, element, layout, mesh)) return;
  reserve_vertices(element.count, reader.remaining(), layout, mesh);
  std::vector<double> values(element.properties.size());
  const auto value = [&values](int index) { return values[static_cast<size_t>(index)]; };
  for (uint64_t record = 0; record < element.count; ++record) {
    reader.at(element.name, record);
    read_record(reader, element, values);
    append_vertex(reader, element, record, layout, value, mesh);
  }
}

// Fan triangulation keeps the polygon's winding: (0, i, i+1) turns the same way as the polygon. `index(i)` is the
// polygon's i-th vertex index, already checked.
template <typename Index>
void append_polygon(uint64_t corners, Index&& index, TriangleMesh& mesh) {
  const uint32_t first = index(0);
  uint32_t previous = index(1);
  for (uint64_t i = 2; i < corners; ++i) {
    const uint32_t current = index(i);
    mesh.indices.insert(mesh.indices.end(), {first, previous, current});
    previous = current;
  }
}

// The face element of a binary body in native byte order holding only its index list (what exporters write): the
// count and the indices are copied out of the bytes in place. Returns false (nothing read) for other layouts.
bool read_faces_native(ply::BodyReader& reader, const ply::Element& element, const ply::Property& list,
                       uint64_t vertex_count, TriangleMesh& mesh) {
  if (!reader.native_order() || element.properties.size() != 1) return false;
  const size_t count_size = ply::size_of(list.count_type), item_size = ply::size_of(list.type);
  mesh.indices.reserve(3 * static_cast<size_t>(std::min<uint64_t>(element.count, reader.remaining())));
  for (uint64_t record = 0; record < element.count; ++record) {
    const auto fail = [&](const std::string& what) {
      reader.at(element.name, record);
      reader.fail(what);
    };
    if (reader.remaining() < count_size) fail("the file ends inside this record (is it truncated?)");
    const double n = ply::native_value(reader.take(count_size), list.count_type);
    if (n < 3) fail("has " + std::to_string(static_cast<long long>(n)) + " vertices; a face needs at least 3");
    if (n > static_cast<double>(reader.remaining() / item_size))
      fail("the file ends inside this record (is it truncated?)");
    const char* items = reader.take(static_cast<size_t>(n) * item_size);
    const auto index = [&](uint64_t i) {
      const double v = ply::native_value(items + i * item_size, list.type);
      if (v < 0 || v >= static_cast<double>(vertex_count))
        fail("refers to vertex " + std::to_string(static_cast<long long>(v)) + " but there are " +
             std::to_string(vertex_count) + " vertices");
      return static_cast<uint32_t>(v);
    };
    append_polygon(static_cast<uint64_t>(n), index, mesh);
  }
  return true;
}

void read_faces(ply::BodyReader& reader, const ply::Element& element, int list_index, uint64_t vertex_count,
                TriangleMesh& mesh) {
  if (read_faces_native(reader, element, element.properties[size_t(list_index)], vertex_count, mesh)) return;
  mesh.indices.reserve(3 * static_cast<size_t>(std::min<uint64_t>(element.count, reader.remaining())));
  std::vector<uint32_t> polygon;
  for (uint64_t record = 0; record < element.count; ++record) {
    reader.at(element.name, record);
    for (size_t p = 0; p < element.properties.size(); ++p) {
      const ply::Property& property = element.properties[p];
      if (static_cast<int>(p) != list_index) {
        if (property.is_list) {
          const double n = reader.read(property.count_type);
          if (n < 0) reader.fail("list '" + property.name + "' has a negative length");
          reader.skip(property.type, static_cast<uint64_t>(n));
        } else {
          reader.skip(property.type, 1);
        }
        continue;
      }
      const double n = reader.read(property.count_type);
      if (n < 3) reader.fail("has " + std::to_string(static_cast<long long>(n)) + " vertices; a face needs at least 3");
      // Every value takes at least one byte: a longer list than the rest of the file is a truncated file.
      if (n > static_cast<double>(reader.remaining()))
        reader.fail("the file ends inside this record (is it truncated?)");
      polygon.clear();
      for (uint64_t i = 0; i < static_cast<uint64_t>(n); ++i) {
        const double index = reader.read(property.type);
        if (index < 0 || index >= static_cast<double>(vertex_count))
          reader.fail("refers to vertex " + std::to_string(static_cast<long long>(index)) + " but there are " +
                      std::to_string(vertex_count) + " vertices");
        polygon.push_back(static_cast<uint32_t>(index));
      }
      append_polygon(polygon.size(), [&polygon](uint64_t i) { return polygon[i]; }, mesh);
    }
  }
}

void skip_element(ply::BodyReader& reader, const ply::Element& element) {
  if (element.properties.empty()) return;  // records of nothing: nothing to skip, however many
  std::vector<double> ignored(element.properties.size());
  for (uint64_t record = 0; record < element.count; ++record) {
    reader.at(element.name, record);
    read_record(reader, element, ignored);
  }
}

}  // namespace

TriangleMesh parse_ply(std::string_view bytes, const std::string& file) {
  const ply::Header header = ply::parse_header(bytes, file);
  const ply::Element* vertex = nullptr;
  const ply::Element* face = nullptr;
  for (const ply::Element& e : header.elements) {
    if (e.name == "vertex") vertex = &e;
    if (e.name == "face") face = &e;
  }
  if (!vertex) throw InputError({file, 0, ""}, "the PLY header declares no 'vertex' element");
  if (!face) throw InputError({file, 0, ""}, "the PLY header declares no 'face' element (a point cloud is not a mesh)");
  if (vertex->count > std::numeric_limits<uint32_t>::max())
    throw InputError({file, vertex->header_line, ""}, "more vertices than 32-bit indices can address");
  const VertexLayout layout = vertex_layout(*vertex, file);

  int list_index = face->index_of("vertex_indices");
  if (list_index < 0) list_index = face->index_of("vertex_index");
  if (list_index < 0)
    throw InputError({file, face->header_line, ""}, "element 'face' has no list property 'vertex_indices'");
  const ply::Property& list = face->properties[static_cast<size_t>(list_index)];
  if (!list.is_list || !ply::is_integer(list.type))
    throw InputError({file, list.header_line, ""}, "'" + list.name + "' must be a list of an integer type");

  TriangleMesh mesh;
  ply::BodyReader reader(bytes, header, file);
  for (const ply::Element& element : header.elements) {
    if (&element == vertex)
      read_vertices(reader, element, layout, mesh);
    else if (&element == face)
      read_faces(reader, element, list_index, vertex->count, mesh);
    else
      skip_element(reader, element);
  }
  if (mesh.indices.empty()) throw InputError({file, face->header_line, ""}, "the file has no faces");
  return mesh;
}

TriangleMesh load_ply(const std::filesystem::path& path) {
  if (has_gzip_extension(path)) {
    // Deflate expands up to 1032:1, so a 1 MB .ply.gz can inflate to 1 GB of bytes no mesh reads. The header says
    // how much body can follow: decompress the header first, then at most what it can need.
    const std::string compressed = read_input_file(path, kMaxBinaryFileBytes);
    const std::string head = gunzip_prefix(compressed, path.string(), kMaxCompressedPlyHeaderBytes);
    const ply::Header header = ply::parse_header(head, path.string());
    const uint64_t body = ply::max_body_bytes(header);
    const uint64_t bound = std::min<uint64_t>(kMaxBinaryFileBytes, header.body_offset + std::min<uint64_t>(
                                                                       body, kMaxBinaryFileBytes));
    return parse_ply(gunzip(compressed, path.string(), bound,
                            bound == kMaxBinaryFileBytes
                                ? "the limit for meshes"
                                : "the most its PLY header's elements can take (lists of up to " +
                                      std::to_string(ply::kMaxMeanListItems) + " items on average" +
                                      (header.format == ply::Format::ascii
                                           ? ", values of up to " + std::to_string(ply::kMaxAsciiValueChars) +
                                                 " characters"
                                           : std::string()) +
                                      "): the rest cannot be part of the mesh"),
                     path.string());
  }
  return parse_ply(read_input_file(path, kMaxBinaryFileBytes), path.string());
}

}  // namespace rimu
