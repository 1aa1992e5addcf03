// Small image files written by tests (PPM, PFM): no image library needed to make them, OpenImageIO reads them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace rimu::test {

/// A binary PPM (8-bit, sRGB-encoded by convention) with the given rows, top row first, in the temp folder.
inline std::filesystem::path write_ppm(const std::string& name, int w, int h, const std::vector<uint8_t>& rgb) {
  const auto path = std::filesystem::temp_directory_path() / ("rimu_test_" + name + ".ppm");
  std::ofstream out(path, std::ios::binary);
  out << "P6 " << w << " " << h << " 255\n";
  out.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size()));
  return path;
}

/// A little-endian PFM (float, linear), rows written bottom to top as the format requires, in the temp folder.
inline std::filesystem::path write_pfm(const std::string& name, int w, int h, const std::vector<float>& rgb_top_first) {
  const auto path = std::filesystem::temp_directory_path() / ("rimu_test_" + name + ".pfm");
  std::ofstream out(path, std::ios::binary);
  out << "PF\n" << w << " " << h << "\n-1.0\n";
  for (int y = h - 1; y >= 0; --y)
    out.write(reinterpret_cast<const char*>(&rgb_top_first[size_t(y) * size_t(w) * 3]), std::streamsize(w * 3 * 4));
  return path;
}

}  // namespace rimu::test
