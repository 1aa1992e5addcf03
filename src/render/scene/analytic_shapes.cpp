// Quadric and box meshes (analytic_shapes.h): vertices on the surface, analytic normals, pbrt-v4's uv.
#include "render/scene/analytic_shapes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace rimu {
namespace {

constexpr double kMaxArcStep = 2.0 * std::numbers::pi / 96.0;
constexpr double kMaxPolarStep = std::numbers::pi / 48.0;

using Vec3d = std::array<double, 3>;
Vec3d vec3(double x, double y, double z) { return {x, y, z}; }
std::array<double, 2> vec2(double u, double v) { return {u, v}; }

// cos φ and sin φ at u·φmax, exactly (1, 0) at φ = 2π so that a full turn's seam column coincides with its first
// (a watertight mesh: no crack for rays, and closed shapes stay closed).
std::pair<double, double> cos_sin(double u, double phimax_rad) {
  if (u == 1.0 && phimax_rad >= 2.0 * std::numbers::pi) return {1.0, 0.0};
  return {std::cos(u * phimax_rad), std::sin(u * phimax_rad)};
}

// Calls add_column(cos φ, sin φ, u) for the columns u = j/n, j = 0…n, of an arc of φmax cut into n =
// arc_segments(φmax) steps (for a full turn the seam column is repeated, so u runs 0 → 1 without wrapping); returns n.
template <typename AddColumn>
int for_each_column(double phimax_rad, AddColumn add_column);

// Two triangles of the cell (a, b, c, d), counter-clockwise seen from the front.
void add_quad(AnalyticMesh& mesh, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
}

}  // namespace

int arc_segments(double angle_rad) { return std::max(1, int(std::ceil(angle_rad / kMaxArcStep - 1e-9))); }

namespace {
template <typename AddColumn>
int for_each_column(double phimax_rad, AddColumn add_column) {
  const int n = arc_segments(phimax_rad);
  for (int j = 0; j <= n; ++j) {
    const double u = double(j) / n;
    const auto [c, s] = cos_sin(u, phimax_rad);
    add_column(c, s, u);
  }
  return n;
}
}  // namespace

AnalyticMesh cylinder_mesh(double radius, double zmin, double zmax, double phimax_rad) {
  AnalyticMesh mesh;
  // Column j holds the vertex at zmin (index 2j) and at zmax (2j + 1).
  const int n = for_each_column(phimax_rad, [&](double c, double s, double u) {
    for (const double z : {zmin, zmax}) {
      mesh.positions.push_back(vec3(radius * c, radius * s, z));
      mesh.normals.push_back(vec3(c, s, 0));
      mesh.uvs.push_back(vec2(u, z == zmin ? 0.0 : 1.0));
    }
  });
  // (φ_j, zmin), (φ_j+1, zmin), (φ_j+1, zmax), (φ_j, zmax): ∂p/∂φ × ∂p/∂z points outward.
  for (uint32_t j = 0; j < uint32_t(n); ++j) add_quad(mesh, 2 * j, 2 * j + 2, 2 * j + 3, 2 * j + 1);
  return mesh;
}

AnalyticMesh disk_mesh(double height, double radius, double inner_radius, double phimax_rad) {
  AnalyticMesh mesh;
  // Column j holds the outer vertex (2j, v = 0) and the inner one (2j + 1, v = 1; the centre when inner = 0, one per
  // column so that u stays the column's).
  const int n = for_each_column(phimax_rad, [&](double c, double s, double u) {
    mesh.positions.push_back(vec3(radius * c, radius * s, height));
    mesh.uvs.push_back(vec2(u, 0.0));
    mesh.positions.push_back(vec3(inner_radius * c, inner_radius * s, height));
    mesh.uvs.push_back(vec2(u, 1.0));
  });
  mesh.normals.assign(mesh.positions.size(), vec3(0, 0, 1));
  for (uint32_t j = 0; j < uint32_t(n); ++j) {
    const uint32_t outer0 = 2 * j, inner0 = 2 * j + 1, outer1 = 2 * j + 2, inner1 = 2 * j + 3;
    mesh.indices.insert(mesh.indices.end(), {inner0, outer0, outer1});  // counter-clockwise seen from +z
    if (inner_radius > 0) mesh.indices.insert(mesh.indices.end(), {inner0, outer1, inner1});
  }
  return mesh;
}

AnalyticMesh sphere_mesh(double radius, double zmin, double zmax, double phimax_rad) {
  AnalyticMesh mesh;
  zmin = std::clamp(zmin, -radius, radius);
  zmax = std::clamp(zmax, -radius, radius);
  const double theta_top = std::acos(std::clamp(zmax / radius, -1.0, 1.0));
  const double theta_bottom = std::acos(std::clamp(zmin / radius, -1.0, 1.0));
  const int rows = std::max(1, int(std::ceil((theta_bottom - theta_top) / kMaxPolarStep - 1e-9)));
  const int columns = arc_segments(phimax_rad);
  const bool top_pole = zmax >= radius, bottom_pole = zmin <= -radius;
  // Row i = 0…rows from the top (v = 1 − i/rows); a pole row has one vertex per column, the others columns + 1.
  std::vector<uint32_t> row_start;
  for (int i = 0; i <= rows; ++i) {
    const bool pole = (i == 0 && top_pole) || (i == rows && bottom_pole);
    row_start.push_back(uint32_t(mesh.positions.size()));
    const double theta = theta_top + (theta_bottom - theta_top) * i / rows;
    for (int j = 0; j < columns + (pole ? 0 : 1); ++j) {
      const double u = (j + (pole ? 0.5 : 0.0)) / columns;
      const auto [c, s] = cos_sin(u, phimax_rad);
      // At a pole sin θ is 0 exactly, so every column's pole vertex is the same point.
      const double sin_theta = pole ? 0.0 : std::sin(theta), cos_theta = pole ? (i == 0 ? 1.0 : -1.0) : std::cos(theta);
      const Vec3d n = vec3(sin_theta * c, sin_theta * s, cos_theta);
      mesh.positions.push_back(vec3(radius * n[0], radius * n[1], radius * n[2]));
      mesh.normals.push_back(n);
      mesh.uvs.push_back(vec2(u, 1.0 - double(i) / rows));
    }
  }
  const auto at = [&](int i, int j) { return row_start[size_t(i)] + uint32_t(j); };
  // Rows run down from +z and columns with φ: (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1) is counter-clockwise
  // seen from outside. Next to a pole the cell is one triangle.
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < columns; ++j) {
      if (i == 0 && top_pole)
        mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      else if (i + 1 == rows && bottom_pole)
        mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
      else
        add_quad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return mesh;
}

AnalyticMesh box_mesh(const Vec3& lo, const Vec3& hi) {
  AnalyticMesh mesh;
  // Per face: the axis of its normal, the sign, and the axes u and v run along (u × v = the outward normal).
  struct Face {
    int normal_axis;
    float sign;
    int u_axis, v_axis;
  };
  static constexpr Face kFaces[6] = {{0, +1, 1, 2}, {0, -1, 2, 1}, {1, +1, 2, 0}, {1, -1, 0, 2}, {2, +1, 0, 1}, {2, -1, 1, 0}};
  for (const Face& face : kFaces) {
    const auto base = uint32_t(mesh.positions.size());
    for (const auto& [u, v] : {std::pair{0, 0}, std::pair{1, 0}, std::pair{1, 1}, std::pair{0, 1}}) {
      Vec3d p{}, n{};
      p[size_t(face.normal_axis)] = face.sign > 0 ? hi[face.normal_axis] : lo[face.normal_axis];
      p[size_t(face.u_axis)] = u ? hi[face.u_axis] : lo[face.u_axis];
      p[size_t(face.v_axis)] = v ? hi[face.v_axis] : lo[face.v_axis];
      n[size_t(face.normal_axis)] = face.sign;
      mesh.positions.push_back(p);
      mesh.normals.push_back(n);
      mesh.uvs.push_back(vec2(u, v));
    }
    add_quad(mesh, base, base + 1, base + 2, base + 3);
  }
  return mesh;
}

TriangleMesh AnalyticMesh::to_triangle_mesh() const {
  TriangleMesh mesh;
  for (const Vec3d& p : positions) mesh.positions.push_back({float(p[0]), float(p[1]), float(p[2])});
  for (const Vec3d& n : normals) mesh.normals.push_back({float(n[0]), float(n[1]), float(n[2])});
  for (const auto& uv : uvs) mesh.uvs.push_back({float(uv[0]), float(uv[1])});
  mesh.indices = indices;
  return mesh;
}

void append_mesh(AnalyticMesh& mesh, const AnalyticMesh& part) {
  const auto base = uint32_t(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
  mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
  mesh.uvs.insert(mesh.uvs.end(), part.uvs.begin(), part.uvs.end());
  for (const uint32_t i : part.indices) mesh.indices.push_back(base + i);
}

void flip_mesh(AnalyticMesh& mesh) {
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  for (Vec3d& n : mesh.normals) n = {-n[0], -n[1], -n[2]};
}

}  // namespace rimu
