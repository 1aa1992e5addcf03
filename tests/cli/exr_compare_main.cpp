// rimu-exr-compare A.exr B.exr [--max-ulps N] [--image-only]: the test scripts' image comparison
// (render/output/exr_compare.h). Prints how many values differ and by how much; exit 0 if no image value is more than N
// float32 ULPs apart (default 0: bit-identical), 1 otherwise or on bad input.
#include <cstdlib>
#include <iostream>
#include <string>

#include "render/output/exr_compare.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: rimu-exr-compare A.exr B.exr [--max-ulps N] [--image-only]\n";
    return 1;
  }
  uint64_t max_ulps = 0;
  bool image_only = false;
  for (int i = 3; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--image-only") image_only = true;
    else if (arg == "--max-ulps" && i + 1 < argc) max_ulps = std::strtoull(argv[++i], nullptr, 10);
    else {
      std::cerr << "rimu-exr-compare: unknown argument '" << arg << "'\n";
      return 1;
    }
  }
  try {
    const rimu::ExrDifference d = rimu::compare_exr(argv[1], argv[2], image_only);
    std::cout << d.different << " of " << d.values << " values differ; largest difference " << d.max_ulps
              << " float32 ULPs" << (d.worst.empty() ? "" : " (" + d.worst + ")") << "\n";
    return d.max_ulps <= max_ulps ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "rimu-exr-compare: " << e.what() << "\n";
    return 1;
  }
}
