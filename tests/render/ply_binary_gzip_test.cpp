// PLY files in the layout exporters write (scalar vertex properties, a face element holding only its index list),
// which binary files in the machine's byte order read through the in-place path of ply_loader.cpp; and .ply.gz.
#include <doctest/doctest.h>
#include <zlib.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "render/scene/gzip_bytes.h"
#include "render/scene/mesh_loader.h"
#include "render/scene/ply_format.h"
#include "render/scene/ply_loader.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;

namespace {

enum class Order { ascii, native, swapped };

template <typename T>
void put(std::string& out, T value, Order order) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (order == Order::swapped)
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  out.append(raw, sizeof(T));
}

const char* format_name(Order order) {
  const bool little = std::endian::native == std::endian::little;
  if (order == Order::ascii) return "ascii";
  return (order == Order::native) == little ? "binary_little_endian" : "binary_big_endian";
}

// Five vertices (float x y z nx ny nz u v) and a quad, a triangle and a pentagon as 'list uchar int'. Vertex 1's
// normal has length 2 (normalised on load). `index_override` replaces the pentagon's last index when >= 0.
std::string compact_ply(Order order, float vertex3_y = 1.0f, int index_override = -1) {
  const float v[5][8] = {{0, 0, 0, 0, 0, 1, 0, 0},   {1, 0, 0, 0, 0, 2, 1, 0},       {1, 1, 0, 0, 0, 1, 1, 1},
                         {0, vertex3_y, 0, 0, 0, 1, 0, 1}, {0.5f, 1.5f, 0, 0, 0, 1, 0.5f, 1.5f}};
  const std::vector<std::vector<int>> faces = {{0, 1, 2, 3}, {0, 1, 2}, {0, 1, 2, 4, index_override >= 0 ? index_override : 3}};
  std::string out = "ply\nformat ";
  out += format_name(order);
  out += " 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
         "property float ny\nproperty float nz\nproperty float u\nproperty float v\nelement face 3\n"
         "property list uchar int vertex_indices\nend_header\n";
  for (const auto& vertex : v) {
    for (float x : vertex) {
      if (order == Order::ascii) {
        out += std::isnan(x) ? std::string("nan") : std::to_string(x);
        out += ' ';
      } else {
        put(out, x, order);
      }
    }
    if (order == Order::ascii) out += '\n';
  }
  for (const auto& f : faces) {
    if (order == Order::ascii) {
      out += std::to_string(f.size());
      for (int i : f) out += ' ' + std::to_string(i);
      out += '\n';
    } else {
      put(out, uint8_t(f.size()), order);
      for (int i : f) put(out, int32_t(i), order);
    }
  }
  return out;
}

std::string gzip(const std::string& bytes) {
  z_stream stream{};
  REQUIRE(deflateInit2(&stream, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) == Z_OK);  // 15 + 16: gzip wrapper
  std::string out(deflateBound(&stream, uLong(bytes.size())) + 64, '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  stream.avail_in = uInt(bytes.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = uInt(out.size());
  REQUIRE(deflate(&stream, Z_FINISH) == Z_STREAM_END);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

// Runs `load`, expecting an InputError whose message holds every fragment.
void expect_input_error(const std::function<void()>& load, std::initializer_list<std::string> fragments) {
  try {
    load();
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const std::string& fragment : fragments)
      CHECK_MESSAGE(message.find(fragment) != std::string::npos, message, " lacks ", fragment);
    return;
  }
  FAIL("no InputError; expected one mentioning ", *fragments.begin());
}

}  // namespace

TEST_CASE("PLY in the exporters' layout: native-order binary (in place), swapped binary and ascii agree") {
  const TriangleMesh native = parse_ply(compact_ply(Order::native), "native.ply");
  // Quad fanned (0 1 2)(0 2 3), the triangle, the pentagon fanned from its first corner.
  CHECK(native.indices == std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 1, 2, 0, 2, 4, 0, 4, 3});
  REQUIRE(native.normals.size() == 5);
  CHECK(native.normals[1] == Vec3(0, 0, 1));  // (0, 0, 2) normalised
  REQUIRE(native.uvs.size() == 5);
  CHECK(native.uvs[4].y == 1.5f);
  // Embree reads the last vertex with a 16-byte load: the loader leaves room for it.
  CHECK(native.positions.capacity() > native.positions.size());
  for (Order order : {Order::swapped, Order::ascii}) {
    CAPTURE(format_name(order));
    const TriangleMesh other = parse_ply(compact_ply(order), "other.ply");
    CHECK(other.indices == native.indices);
    CHECK(other.positions == native.positions);
    CHECK(other.normals == native.normals);
    REQUIRE(other.uvs.size() == native.uvs.size());
    for (size_t i = 0; i < other.uvs.size(); ++i) CHECK((other.uvs[i].x == native.uvs[i].x && other.uvs[i].y == native.uvs[i].y));
  }
}

TEST_CASE("PLY native-order binary errors name the element, the record and the byte") {
  expect_input_error([] { parse_ply(compact_ply(Order::native, 1.0f, 5), "bad.ply"); },
                     {"bad.ply", "face 2", "refers to vertex 5 but there are 5 vertices", "byte"});
  expect_input_error([] { parse_ply(compact_ply(Order::native, std::nanf("")), "bad.ply"); },
                     {"bad.ply", "vertex 3", "not finite"});
  std::string two_corners = compact_ply(Order::native);
  two_corners[two_corners.size() - 5 * 4 - 1] = 2;  // the pentagon's count byte
  expect_input_error([&] { parse_ply(two_corners, "bad.ply"); }, {"bad.ply", "face 2", "has 2 vertices"});
  // Every shorter file is an error; only the whole file loads (a vertex record is 32 bytes, a triangle 13).
  const std::string whole = compact_ply(Order::native);
  const size_t body = whole.find("end_header\n") + 11;
  for (size_t length = body; length <= whole.size(); ++length) {
    CAPTURE(length);
    if (length == whole.size()) {
      CHECK(parse_ply(whole, "whole.ply").validate().empty());
    } else {
      const std::string element = length < body + 5 * 32 ? "vertex " + std::to_string((length - body) / 32) : "face ";
      expect_input_error([&] { parse_ply(whole.substr(0, length), "cut.ply"); }, {"cut.ply", element, "truncated"});
    }
  }
}

TEST_CASE(".ply.gz meshes load like the .ply, truncated, corrupt and mislabelled ones are input errors") {
  test::ScratchFolder dir("ply_gzip");
  const std::string ply = compact_ply(Order::native);
  const std::string compressed = gzip(ply);
  const TriangleMesh plain = load_mesh(dir.write("mesh.ply", ply));
  const TriangleMesh unzipped = load_mesh(dir.write("mesh.PLY.GZ", compressed));
  CHECK(unzipped.indices == plain.indices);
  CHECK(unzipped.positions == plain.positions);
  // Two concatenated gzip members are one stream (gzip(1) and zcat treat them so).
  CHECK(gunzip(compressed + gzip("tail"), "two.gz", 1 << 20) == ply + "tail");

  expect_input_error([&] { load_mesh(dir.write("cut.ply.gz", compressed.substr(0, compressed.size() / 2))); },
                     {"cut.ply.gz", "truncated"});
  // The last 8 bytes are the CRC-32 and the length: dropping them is a truncation, damaging the CRC corruption.
  expect_input_error([&] { load_mesh(dir.write("nocrc.ply.gz", compressed.substr(0, compressed.size() - 8))); },
                     {"nocrc.ply.gz", "truncated"});
  std::string bad_crc = compressed;
  bad_crc[bad_crc.size() - 6] ^= 0x55;
  expect_input_error([&] { load_mesh(dir.write("crc.ply.gz", bad_crc)); }, {"crc.ply.gz", "corrupt"});
  std::string garbled = compressed;
  for (size_t i = 10; i < 30 && i < garbled.size(); ++i) garbled[i] = char(0xff);
  expect_input_error([&] { load_mesh(dir.write("garbled.ply.gz", garbled)); }, {"garbled.ply.gz"});
  expect_input_error([&] { load_mesh(dir.write("plain.ply.gz", ply)); }, {"plain.ply.gz", "not gzip-compressed"});
  expect_input_error([&] { gunzip(compressed, "limit.gz", 100); }, {"limit.gz", "more than"});
  // A gzip stream that decompresses to a broken PLY reports the PLY error under the .gz name.
  expect_input_error([&] { load_mesh(dir.write("inner.ply.gz", gzip(ply.substr(0, ply.size() - 3)))); },
                     {"inner.ply.gz", "face 2", "truncated"});
  expect_input_error([&] { load_mesh(dir.write("mesh.obj.gz", gzip("v 0 0 0\n"))); }, {"mesh.obj.gz", "unsupported"});
}

TEST_CASE(".ply.gz: decompression stops at what the PLY header can need, not at the 16 GiB file limit") {
  // A 3-vertex, 1-face header followed by 8 MiB of zeros: deflate shrinks the zeros ~1000:1, so a file of a few
  // KiB (1 MB would inflate to 1 GB) makes the reader decompress everything before the PLY parser stops it.
  test::ScratchFolder dir("ply_gzip_bomb");
  const std::string mesh = compact_ply(Order::native);
  const ply::Header header = ply::parse_header(mesh, "mesh.ply");
  const uint64_t body_bound = ply::max_body_bytes(header);
  // The bound covers the real body (exact binary records, lists of at most 255 items), and is small.
  CHECK(mesh.size() - header.body_offset <= body_bound);
  CHECK(body_bound < 64 * 1024);
  const std::string bomb = gzip(mesh + std::string(size_t(8) << 20, '\0'));
  CHECK(bomb.size() < 64 * 1024);
  expect_input_error([&] { load_mesh(dir.write("bomb.ply.gz", bomb)); },
                     {"bomb.ply.gz", "decompresses to more than", "PLY header"});
  // The same mesh with its trailing bytes within the bound still reaches the PLY reader (which reads what the
  // header declares).
  CHECK(load_mesh(dir.write("mesh.ply.gz", gzip(mesh))).indices == parse_ply(mesh, "mesh.ply").indices);
  // An ascii header counts 64 characters per value; the header must be in the first 1 MiB.
  const std::string ascii = compact_ply(Order::ascii);
  CHECK(ascii.size() - ply::parse_header(ascii, "a.ply").body_offset <= ply::max_body_bytes(ply::parse_header(ascii, "a.ply")));
  expect_input_error([&] { load_mesh(dir.write("long.ply.gz", gzip("ply\n" + std::string(2 << 20, ' ')))); },
                     {"long.ply.gz", "end_header"});
  // Counts near 2^64 saturate rather than wrap to a small bound.
  ply::Header huge;
  huge.elements.push_back({"vertex", ~uint64_t(0), {{"x", ply::Type::float64, false, ply::Type::uint8, 3}}, 2});
  CHECK(ply::max_body_bytes(huge) == ~uint64_t(0));
}
