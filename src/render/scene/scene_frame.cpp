#include "render/scene/scene_frame.h"

#include <cstdio>

#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu {

std::string substitute_frame(const std::string& text, std::optional<int> frame, const std::string& where) {
  static const std::string kOpen = "${frame";
  std::string out;
  size_t at = 0;
  while (true) {
    const size_t start = text.find(kOpen, at);
    if (start == std::string::npos) break;
    out += text.substr(at, start - at);
    const size_t close = text.find('}', start);
    const std::string token = text.substr(start, close == std::string::npos ? std::string::npos : close - start + 1);
    int digits = 0;
    if (token == "${frame}") {
      digits = 0;
    } else if (token.size() == 10 && token[7] == ':' && token[8] >= '1' && token[8] <= '9' && token[9] == '}') {
      digits = token[8] - '0';
    } else {
      throw InputError({where, 0, ""}, "malformed frame placeholder '" + token +
                                           "': expected ${frame} or ${frame:N} (N = 1-9 digits, zero-padded)");
    }
    if (!frame)
      throw InputError({where, 0, ""}, "uses " + token + " but no frame number was given (--frame N)");
    char number[32];
    std::snprintf(number, sizeof(number), "%0*d", digits, *frame);
    out += number;
    at = close + 1;
  }
  return out + text.substr(at);
}

std::string scene_text_for_frame(const std::filesystem::path& path, std::optional<int> frame) {
  // The same checks as every scene read (a regular file, a size limit): a FIFO or /dev/zero never hangs here.
  return substitute_frame(read_input_file(path, kMaxJsonFileBytes), frame, path.string());
}

}  // namespace rimu
