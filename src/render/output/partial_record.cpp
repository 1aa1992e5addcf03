#include "render/output/partial_record.h"

#include <cstdio>

#include "spectral/error.h"

namespace rimu {

SampleRange parse_sample_range(const std::string& text, const std::string& option) {
  SampleRange r;
  char colon = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &r.begin, &colon, &r.end, &extra) != 3 || colon != ':' || r.begin < 0 ||
      r.end <= r.begin || r.end > (1 << 24))
    throw InputError({"", 0, option},
                     "expected sample indices BEGIN:END with 0 <= BEGIN < END <= 16777216 (END exclusive), e.g. "
                     "0:256; got '" + text + "'");
  return r;
}

double parse_duration_s(const std::string& text, const std::string& option) {
  double value = 0;
  char unit = 's', extra = 0;
  const int n = std::sscanf(text.c_str(), "%lf%c%c", &value, &unit, &extra);
  const double scale = unit == 's' ? 1.0 : unit == 'm' ? 60.0 : unit == 'h' ? 3600.0 : 0.0;
  if ((n != 1 && n != 2) || scale == 0.0 || !(value > 0) || value * scale > 1e9)
    throw InputError({"", 0, option}, "expected a positive duration such as 30s, 10m or 1h; got '" + text + "'");
  return value * scale;
}

std::string sample_ranges_text(const std::vector<SampleRange>& ranges) {
  std::string text;
  for (const SampleRange& r : ranges) text += (text.empty() ? "" : ",") + r.text();
  return text;
}

std::vector<SampleRange> parse_sample_ranges(const std::string& text, const std::string& where) {
  std::vector<SampleRange> ranges;
  if (text.empty()) return ranges;  // a checkpoint written before its first pass ended
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = text.find(',', start);
    ranges.push_back(parse_sample_range(text.substr(start, comma - start), where));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return ranges;
}

}  // namespace rimu
