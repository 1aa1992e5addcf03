#include "spectral/upsampling/upsampling_table.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>

#include "spectral/error.h"

namespace rimu {
namespace {

constexpr char kMagic[8] = {'R', 'I', 'M', 'U', 'U', 'P', 'S', '1'};
constexpr size_t kNameBytes = 16;

template <typename T>
void put(std::ofstream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <typename T>
void get(std::ifstream& in, T& value, const std::filesystem::path& path) {
  if (!in.read(reinterpret_cast<char*>(&value), sizeof(T)))
    throw InputError({path.string(), 0, ""}, "upsampling table is truncated (regenerate it: see data/upsampling/README.md)");
}

}  // namespace

double UpsamplingTable::radius_of_row(int r) const {
  const double u = 1.0 - double(r) / (radius_count - 1);
  return 1.0 - u * u;
}

KnotValues UpsamplingTable::interpolate(double angle_rad, double relative_radius) const {
  // Angle: periodic, uniform. Radius: rows are uniform in u = 1 − √(1 − ρ), which finds the cell.
  double a = angle_rad / (2 * std::numbers::pi) * angle_count;
  a -= std::floor(a / angle_count) * angle_count;
  const int a0 = std::min(int(a), angle_count - 1);
  const int a1 = (a0 + 1) % angle_count;
  const double ta = std::clamp(a - a0, 0.0, 1.0);
  const double rho = std::clamp(relative_radius, 0.0, 1.0);
  const double u = (1.0 - std::sqrt(1.0 - rho)) * (radius_count - 1);
  const int r0 = std::min(int(u), radius_count - 2);
  // Weights linear in ρ (not in u): u(ρ) has an infinite slope at ρ = 1, which would make the spectrum's
  // derivative there infinite too.
  const double tr = std::clamp((rho - radius_of_row(r0)) / (radius_of_row(r0 + 1) - radius_of_row(r0)), 0.0, 1.0);
  const size_t corners[4] = {entry(a0, r0), entry(a1, r0), entry(a0, r0 + 1), entry(a1, r0 + 1)};
  const double weights[4] = {(1 - ta) * (1 - tr), ta * (1 - tr), (1 - ta) * tr, ta * tr};
  KnotValues out{};
  for (int c = 0; c < 4; ++c) {
    if (weights[c] == 0.0) continue;
    const double w = weights[c] / (65535.0 * luminance_limits[corners[c]]);
    const uint16_t* q = &shapes[corners[c] * kUpsampleKnotCount];
    for (int i = 0; i < kUpsampleKnotCount; ++i) out[i] += w * q[i];
  }
  return out;
}

void UpsamplingTable::write(const std::filesystem::path& path) const {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError({path.string(), 0, ""}, "cannot write the upsampling table");
  out.write(kMagic, sizeof kMagic);
  put(out, uint32_t(angle_count));
  put(out, uint32_t(radius_count));
  put(out, uint32_t(kUpsampleKnotCount));
  put(out, uint32_t(hull.size()));
  put(out, white.x);
  put(out, white.y);
  put(out, usable_fraction);
  char name[kNameBytes] = {};
  std::memcpy(name, white_name.data(), std::min(white_name.size(), kNameBytes - 1));
  out.write(name, kNameBytes);
  for (const Chromaticity& v : hull) put(out, v.x), put(out, v.y);
  out.write(reinterpret_cast<const char*>(luminance_limits.data()), std::streamsize(luminance_limits.size() * sizeof(float)));
  out.write(reinterpret_cast<const char*>(shapes.data()), std::streamsize(shapes.size() * sizeof(uint16_t)));
  out.close();  // the last buffer is written here: a full disk shows only now
  if (!out) throw std::runtime_error("cannot write '" + path.string() + "': writing the upsampling table failed");
}

UpsamplingTable UpsamplingTable::read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError({path.string(), 0, ""},
                     "cannot open the upsampling table (regenerate it: see data/upsampling/README.md)");
  char magic[8];
  if (!in.read(magic, 8) || std::memcmp(magic, kMagic, 8) != 0)
    throw InputError({path.string(), 0, ""}, "not a Rimu upsampling table (expected the magic RIMUUPS1)");
  UpsamplingTable t;
  uint32_t angles, radii, knots, hull_count;
  get(in, angles, path), get(in, radii, path), get(in, knots, path), get(in, hull_count, path);
  if (knots != kUpsampleKnotCount || angles < 3 || radii < 2 || hull_count < 3 || angles > 100000 || radii > 100000 ||
      hull_count > 10000)
    throw InputError({path.string(), 0, ""}, "upsampling table header has impossible sizes (knots " +
                                                 std::to_string(knots) + ", expected 95)");
  t.angle_count = int(angles), t.radius_count = int(radii);
  get(in, t.white.x, path), get(in, t.white.y, path), get(in, t.usable_fraction, path);
  char name[kNameBytes];
  if (!in.read(name, kNameBytes)) throw InputError({path.string(), 0, ""}, "upsampling table is truncated");
  t.white_name.assign(name, strnlen(name, kNameBytes));
  t.hull.resize(hull_count);
  for (Chromaticity& v : t.hull) get(in, v.x, path), get(in, v.y, path);
  const size_t entries = size_t(angles) * radii;
  t.luminance_limits.resize(entries);
  t.shapes.resize(entries * kUpsampleKnotCount);
  if (!in.read(reinterpret_cast<char*>(t.luminance_limits.data()), std::streamsize(entries * sizeof(float))) ||
      !in.read(reinterpret_cast<char*>(t.shapes.data()), std::streamsize(t.shapes.size() * sizeof(uint16_t))))
    throw InputError({path.string(), 0, ""}, "upsampling table is truncated");
  for (float limit : t.luminance_limits)
    if (!(limit > 0.0f && std::isfinite(limit)))
      throw InputError({path.string(), 0, ""}, "upsampling table holds a non-positive brightness limit");
  return t;
}

}  // namespace rimu
