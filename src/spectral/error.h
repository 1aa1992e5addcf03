// User-facing errors: what went wrong and where it came from.
//
// Rimu has two tiers of errors (see docs/architecture.md). Invariants are assertions. Everything a user
// can get wrong -- a scene, a spectrum file, a CLI flag -- is an InputError that names the file, the line
// and/or the key path, and is raised at load time, never inside the per-sample loop. A failure that is not the
// user's input (a library Rimu uses: Embree, OpenEXR, OCIO, OIIO; or the machine) is a RenderError.
#pragma once

#include <stdexcept>
#include <string>

namespace rimu {

/// Where a piece of user input came from. Any field may be empty/zero when unknown.
struct SourceLocation {
  std::string file;  ///< path as the user gave it
  int line = 0;      ///< 1-based line number; 0 = not applicable
  std::string key;   ///< JSON key path ("/materials/2/albedo") or CLI option ("--cct")

  /// "file:line: key" with the missing parts left out.
  std::string describe() const;
};

/// Bad user input. The message says what was expected; where() says where.
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& what);
  const SourceLocation& where() const noexcept { return where_; }
  /// The bare explanation, without the location prefix that what() carries.
  const std::string& explanation() const noexcept { return explanation_; }

 private:
  SourceLocation where_;
  std::string explanation_;
};

/// Tools exit with status 2 on a RenderError (1 is reserved for bad input, InputError).
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rimu
