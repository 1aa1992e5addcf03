// The size line of a Radiance HDR (.hdr) file, read by Rimu itself: the file goes to the FreeImage module only when
// its pixels are stored in the standard orientation ("-Y height +X width": rows top first, left to right), the one
// orientation whose rows FreeImage returns as OpenImageIO does; any other goes to OpenImageIO. Shared by the router
// (image_library.cpp) and the module (freeimage_module.cpp), which also checks FreeImage's size against it.
#pragma once

#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

namespace rimu {

struct RadianceSize {
  long long width = 0, height = 0;
};

/// The size of a Radiance file stored "-Y height +X width", or nullopt (not a Radiance file, another orientation,
/// no size line within the first 64 KiB, or a size that is not positive).
inline std::optional<RadianceSize> radiance_standard_size(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[2] = {0, 0};
  if (!in.read(magic, 2) || magic[0] != '#' || magic[1] != '?') return std::nullopt;  // read no more of other files
  std::string head(65536, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(in.gcount()));
  const size_t blank = head.find("\n\n");  // the header's lines end with an empty one
  if (blank == std::string::npos) return std::nullopt;
  const size_t line = blank + 2, end = head.find('\n', line);
  if (end == std::string::npos) return std::nullopt;
  RadianceSize size;
  char tail = 0;
  const std::string text = head.substr(line, end - line);
  if (std::sscanf(text.c_str(), "-Y %lld +X %lld%c", &size.height, &size.width, &tail) != 2) return std::nullopt;
  if (size.width <= 0 || size.height <= 0) return std::nullopt;
  return size;
}

}  // namespace rimu
