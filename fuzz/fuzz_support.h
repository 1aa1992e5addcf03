// What every fuzz target shares: the rule for which exceptions are expected, and a private temporary file for
// readers that only take a path. See docs/fuzzing.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

#include "spectral/error.h"

namespace rimu::fuzz {

/// Runs `read` on one input. InputError is the documented answer to bad input and is not a finding; any other
/// exception is (bad_alloc included: libFuzzer's -rss_limit_mb and -malloc_limit_mb report memory separately), so
/// it is printed and turned into an abort, which libFuzzer records as a crash with the input that caused it.
template <typename Read>
int run_reader(const char* target, Read&& read) {
  try {
    read();
  } catch (const InputError& e) {
    // RIMU_FUZZ_VERBOSE=1 prints the messages, to check that seeds load or to read what a mutated input says.
    static const bool verbose = std::getenv("RIMU_FUZZ_VERBOSE") != nullptr;
    if (verbose) std::fprintf(stderr, "%s: InputError: %s\n", target, e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: unexpected exception (not rimu::InputError): %s\n", target, e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "%s: unexpected exception of unknown type\n", target);
    std::abort();
  }
  return 0;
}

/// The input as text (may hold NUL bytes: the readers must cope with them).
inline std::string_view as_text(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Writes the input to a file private to this process (for readers that only take a path) and returns its path.
/// The same file is overwritten for every input and removed when the process exits normally.
std::filesystem::path write_private_file(const uint8_t* data, size_t size, const std::string& extension);

/// The folder write_private_file writes into (made 0700 by mkdtemp on first use, removed at normal exit): a target
/// may put the files its input refers to beside the input.
const std::filesystem::path& private_folder();

}  // namespace rimu::fuzz
