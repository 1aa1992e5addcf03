// Mesh loading at scale: a generated binary PLY grid (written here, never committed), its load speed on one core,
// the memory held per triangle, Embree's own allocations, and the cost of instancing the mesh many times.
// A plain main(): each figure is one whole load, measured once per process so that the peak RSS belongs to it.
//
//   rimu-mesh-scale-bench generate grid.ply 10000000        # a 10 M-triangle binary little-endian PLY
//   rimu-mesh-scale-bench generate-big-endian grid_be.ply 10000000   # the same big-endian (the general path)
//   rimu-mesh-scale-bench load grid.ply                     # parse, then build the BVH; prints the figures
//   rimu-mesh-scale-bench instances grid.ply 1000           # one prototype, 1,000 instances of it
#include <sys/resource.h>
#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "bench_support.h"
#include "render/scene/embree_scene.h"
#include "render/scene/ply_loader.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// CPU time of the calling thread: what one core spent, however busy the machine is (the wall time is not).
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Peak resident set of this process so far (getrusage reports kB on Linux).
double peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) * 1024.0;
}

// Current resident set, from /proc/self/statm (pages).
double current_rss_bytes() {
  std::ifstream in("/proc/self/statm");
  long total = 0, resident = 0;
  in >> total >> resident;
  return double(resident) * 4096.0;
}

// A rippled square grid of (n+1)² vertices and 2n² triangles with n chosen so that 2n² ≥ triangles: x, y, z as
// float32; faces as 'list uchar int' (the layout pbrt-v4's exporters write). Written in one buffered pass.
// Reverses the bytes of each 4-byte word in [begin, end): little-endian words to big-endian.
void swap_words(unsigned char* begin, unsigned char* end) {
  for (unsigned char* p = begin; p + 4 <= end; p += 4) std::swap(p[0], p[3]), std::swap(p[1], p[2]);
}

int generate(const std::string& path, long long triangles, bool big_endian) {
  const long long n = (long long)std::ceil(std::sqrt(double(triangles) / 2.0));
  const long long vertices = (n + 1) * (n + 1), faces = 2 * n * n;
  std::FILE* out = std::fopen(path.c_str(), "wb");
  if (!out) {
    std::cerr << "cannot write " << path << "\n";
    return 1;
  }
  std::fprintf(out,
               "ply\nformat %s 1.0\ncomment rimu-mesh-scale-bench grid %lld\nelement vertex %lld\n"
               "property float x\nproperty float y\nproperty float z\nelement face %lld\n"
               "property list uchar int vertex_indices\nend_header\n",
               big_endian ? "binary_big_endian" : "binary_little_endian", n, vertices, faces);
  std::vector<float> row(3 * size_t(n + 1));
  for (long long j = 0; j <= n; ++j) {
    for (long long i = 0; i <= n; ++i) {
      const float x = float(i) / float(n), y = float(j) / float(n);
      row[3 * i] = x;
      row[3 * i + 1] = y;
      row[3 * i + 2] = 0.01f * std::sin(40.0f * x) * std::cos(40.0f * y);
    }
    if (big_endian) {
      auto* bytes = reinterpret_cast<unsigned char*>(row.data());
      swap_words(bytes, bytes + 4 * row.size());
    }
    std::fwrite(row.data(), sizeof(float), row.size(), out);
  }
  std::vector<unsigned char> record(2 * 13 * size_t(n));
  for (long long j = 0; j < n; ++j) {
    unsigned char* p = record.data();
    for (long long i = 0; i < n; ++i) {
      const int v00 = int(j * (n + 1) + i), v10 = v00 + 1, v01 = v00 + int(n + 1), v11 = v01 + 1;
      const int triangles_of_cell[2][3] = {{v00, v10, v11}, {v00, v11, v01}};
      for (const auto& tri : triangles_of_cell) {
        *p++ = 3;
        std::memcpy(p, tri, 12);
        if (big_endian) swap_words(p, p + 12);
        p += 12;
      }
    }
    std::fwrite(record.data(), 1, record.size(), out);
  }
  const bool ok = std::fclose(out) == 0;
  std::cout << path << ": " << faces << " triangles, " << vertices << " vertices\n";
  return ok ? 0 : 1;
}

double mesh_bytes(const rimu::TriangleMesh& m) {
  return double(m.positions.capacity() * sizeof(rimu::Vec3) + m.normals.capacity() * sizeof(rimu::Vec3) +
                m.uvs.capacity() * sizeof(rimu::Vec2) + m.indices.capacity() * sizeof(uint32_t));
}

void print_machine() {
  std::cout << "machine: " << rimu::bench::machine_description() << "; load " << rimu::bench::load_average() << "\n"
            << "build: " << rimu::bench::build_description() << "\n";
}

int load(const std::string& path) {
  print_machine();
  const double rss_before = current_rss_bytes();
  auto start = Clock::now();
  const double cpu_start = thread_cpu_seconds();
  rimu::TriangleMesh mesh = rimu::load_ply(path);
  const double parse_s = seconds_since(start), parse_cpu_s = thread_cpu_seconds() - cpu_start;
  const double triangles = double(mesh.triangle_count());
  const double held = mesh_bytes(mesh);
  const double peak_after_parse = peak_rss_bytes();
  std::cout << "parse (one thread, file read included): " << triangles << " triangles, " << mesh.positions.size()
            << " vertices in " << parse_cpu_s << " s CPU = " << triangles / parse_cpu_s / 1e6
            << " M triangles/s per core; wall " << parse_s << " s = " << triangles / parse_s / 1e6
            << " M triangles/s\n"
            << "mesh arrays: " << held / triangles << " bytes/triangle\n"
            << "peak RSS after parse: " << (peak_after_parse - rss_before) / triangles << " bytes/triangle above start ("
            << peak_after_parse / 1e6 << " MB)\n";
  start = Clock::now();
  rimu::EmbreeScene scene;
  scene.add_mesh(std::move(mesh), 0, -1);
  scene.commit();
  const double build_s = seconds_since(start);
  const double embree = double(scene.embree_bytes());
  const double rss = current_rss_bytes(), peak = peak_rss_bytes();
  std::cout << "BVH build: " << build_s << " s (Embree's threads)\n"
            << "Embree allocations now: " << embree / triangles << " bytes/triangle\n"
            << "RSS after build: " << (rss - rss_before) / triangles << " bytes/triangle above start; minus Embree: "
            << (rss - rss_before - embree) / triangles << "\n"
            << "peak RSS: " << peak / 1e6 << " MB = " << (peak - rss_before) / triangles << " bytes/triangle\n";
  return 0;
}

int instances(const std::string& path, int count) {
  print_machine();
  const double rss_before = current_rss_bytes();
  auto start = Clock::now();
  std::vector<std::pair<rimu::TriangleMesh, int>> meshes;
  meshes.emplace_back(rimu::load_ply(path), 0);
  const double triangles = double(meshes.front().first.triangle_count());
  rimu::EmbreeScene scene;
  const int prototype = scene.add_prototype(std::move(meshes));
  const double prototype_s = seconds_since(start);
  const double rss_prototype = current_rss_bytes();
  start = Clock::now();
  const int side = int(std::ceil(std::sqrt(double(count))));
  for (int k = 0; k < count; ++k)
    scene.add_instance(prototype, rimu::Transform::translate({1.5f * float(k % side), 1.5f * float(k / side), 0.0f}));
  scene.commit();
  const double instances_s = seconds_since(start);
  const double rss = current_rss_bytes(), peak = peak_rss_bytes();
  std::cout << "prototype: " << triangles << " triangles loaded and built in " << prototype_s << " s, RSS "
            << (rss_prototype - rss_before) / 1e6 << " MB\n"
            << count << " instances added and top level built in " << instances_s << " s\n"
            << "RSS after: " << (rss - rss_before) / 1e6 << " MB (" << (rss - rss_prototype) / count
            << " bytes per instance above the prototype); peak " << peak / 1e6 << " MB; Embree "
            << double(scene.embree_bytes()) / 1e6 << " MB\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "generate" && argc == 4) return generate(argv[2], std::atoll(argv[3]), false);
    if (mode == "generate-big-endian" && argc == 4) return generate(argv[2], std::atoll(argv[3]), true);
    if (mode == "load" && argc == 3) return load(argv[2]);
    if (mode == "instances" && argc == 4) return instances(argv[2], std::atoi(argv[3]));
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  std::cerr << "usage: rimu-mesh-scale-bench generate[-big-endian] OUT.ply TRIANGLES | load FILE.ply | instances "
               "FILE.ply COUNT\n";
  return 1;
}
