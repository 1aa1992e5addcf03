#include "spectral/error.h"

namespace rimu {

std::string SourceLocation::describe() const {
  std::string out = file;
  if (line > 0) {
    out.append(file.empty() ? "line " : ":");
    out.append(std::to_string(line));
  }
  if (!key.empty()) {
    if (!out.empty()) out.append(": ");
    out.append(key);
  }
  return out;
}

namespace {
std::string with_location(const SourceLocation& where, const std::string& what) {
  const std::string prefix = where.describe();
  return prefix.empty() ? what : prefix + ": " + what;
}
}  // namespace

InputError::InputError(SourceLocation where, const std::string& what)
    : std::runtime_error(with_location(where, what)), where_(std::move(where)), explanation_(what) {}

}  // namespace rimu
