#include "render/image/image_error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>

#include "spectral/colorimetry/cielab.h"
#include "spectral/colorimetry/delta_e.h"

namespace rimu {

XyzImage XyzImage::from_film(const Film& film) {
  XyzImage image;
  const PixelBounds& b = film.pixel_bounds();
  image.width = b.width();
  image.height = b.height();
  for (int y = b.y0; y < b.y1; ++y)
    for (int x = b.x0; x < b.x1; ++x) {
      const auto v = film.pixel_value(x, y);
      image.pixels.push_back({v[0], v[1], v[2]});
    }
  return image;
}

void XyzImage::write_raw(const std::string& path) const {
  std::ofstream out(path, std::ios::binary);
  const int32_t dims[2] = {width, height};
  out.write(reinterpret_cast<const char*>(dims), sizeof dims);
  out.write(reinterpret_cast<const char*>(pixels.data()), std::streamsize(pixels.size() * sizeof(Xyz)));
}

bool XyzImage::read_raw(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  int32_t dims[2] = {0, 0};
  if (!in.read(reinterpret_cast<char*>(dims), sizeof dims) || dims[0] <= 0 || dims[1] <= 0) return false;
  std::vector<Xyz> data(static_cast<size_t>(dims[0]) * static_cast<size_t>(dims[1]));
  if (!in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size() * sizeof(Xyz)))) return false;
  width = dims[0];
  height = dims[1];
  pixels = std::move(data);
  return true;
}

ImageError image_error(const XyzImage& image, const XyzImage& reference, const Xyz& white) {
  ImageError e;
  const size_t n = reference.pixels.size();
  if (n == 0 || image.pixels.size() != n) return e;
  double mean_y = 0;
  for (const Xyz& r : reference.pixels) mean_y += r.y;
  mean_y /= double(n);
  const double floor2 = (0.01 * mean_y) * (0.01 * mean_y);
  double rel = 0, sq = 0;
  std::vector<double> delta_e(n);
  for (size_t i = 0; i < n; ++i) {
    const Xyz& v = image.pixels[i];
    const Xyz& r = reference.pixels[i];
    const double d[3] = {v.x - r.x, v.y - r.y, v.z - r.z};
    const double rr[3] = {r.x, r.y, r.z};
    for (int k = 0; k < 3; ++k) {
      rel += d[k] * d[k] / (rr[k] * rr[k] + floor2);
      sq += d[k] * d[k];
    }
    delta_e[i] = delta_e_2000(lab_of(v, white), lab_of(r, white));
  }
  e.relative_mse = rel / double(3 * n);
  e.rmse_xyz = std::sqrt(sq / double(3 * n));
  double sum_de = 0;
  for (double d : delta_e) sum_de += d;
  e.mean_delta_e2000 = sum_de / double(n);
  const size_t k95 = std::min(n - 1, size_t(std::ceil(0.95 * double(n))) - 1);
  std::nth_element(delta_e.begin(), delta_e.begin() + std::ptrdiff_t(k95), delta_e.end());
  e.p95_delta_e2000 = delta_e[k95];
  return e;
}

std::map<int, Xyz> group_means(const XyzImage& image, const std::vector<int>& groups) {
  std::map<int, Xyz> sums;
  std::map<int, int> counts;
  for (size_t i = 0; i < image.pixels.size() && i < groups.size(); ++i) {
    if (groups[i] < 0) continue;
    Xyz& s = sums[groups[i]];
    s.x += image.pixels[i].x;
    s.y += image.pixels[i].y;
    s.z += image.pixels[i].z;
    ++counts[groups[i]];
  }
  for (auto& [group, s] : sums) {
    const double c = counts[group];
    s = {s.x / c, s.y / c, s.z / c};
  }
  return sums;
}

Xyz scene_white(const XyzImage& reference, const Xyz& white_xyz) {
  std::vector<double> y;
  for (const Xyz& p : reference.pixels) y.push_back(p.y);
  if (y.empty() || !(white_xyz.y > 0)) return {0.9505, 1.0, 1.089};
  const size_t k = std::min(y.size() - 1, size_t(0.95 * double(y.size())));
  std::nth_element(y.begin(), y.begin() + std::ptrdiff_t(k), y.end());
  const double scale = y[k] / white_xyz.y;
  return {white_xyz.x * scale, white_xyz.y * scale, white_xyz.z * scale};
}

}  // namespace rimu
