// Failures that are not the user's input: a library Rimu uses (Embree, OpenEXR, OCIO, OIIO) or the machine.
#pragma once

#include <stdexcept>

namespace rimu {

/// Tools exit with status 2 on a RenderError (1 is reserved for bad input, rimu::InputError).
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rimu
