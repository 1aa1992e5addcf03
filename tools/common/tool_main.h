// The one main() every Rimu tool runs through: it parses the command line, runs the tool and turns every outcome
// into the documented exit code and a message, so that no tool aborts on an exception it forgot to catch.
//
//   0  success (also --help and --version)
//   1  bad input: a command-line error (unknown option or subcommand, a value CLI11 cannot parse) or an InputError
//      from the libraries (the message names the file, line, key or option)
//   2  a failure of the machine or a library: anything else thrown (std::bad_alloc included), or standard output
//      that could not be written (a full disk, a closed pipe's error)
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <iosfwd>
#include <string>

namespace rimu {

/// A tool's name (the message prefix, e.g. "rimu-light") and its one-paragraph description for --help.
struct ToolInfo {
  std::string name;
  std::string description;
};

/// The text --version prints: "<tool> <version> (commit <git commit>)".
std::string tool_version_text(const std::string& tool_name);

/// Builds the CLI11 application (with --help and --version), lets `declare` add the options, parses `argv`, runs
/// `body`, then flushes standard output and checks that everything written to it arrived. Returns the exit code
/// above; messages go to `err` prefixed with the tool's name. Never throws.
/// Data is loaded by `body`, after parsing, so --help and --version work without any data files.
int run_tool(const ToolInfo& tool, int argc, const char* const* argv, const std::function<void(CLI::App&)>& declare,
             const std::function<void()>& body, std::ostream& err);

/// run_tool() with messages on standard error.
int run_tool(const ToolInfo& tool, int argc, const char* const* argv, const std::function<void(CLI::App&)>& declare,
             const std::function<void()>& body);

/// The same for an application the tool has built and declared itself (its options bound to variables of main):
/// adds --version, parses, runs `body`, checks standard output. Messages go to standard error.
int run_tool(const std::string& name, CLI::App& app, int argc, const char* const* argv,
             const std::function<void()>& body);

/// Flushes std::cout and C's stdout and throws std::runtime_error (with the system's reason) if any write to
/// standard output failed since the program started. run_tool() calls it after the body.
void flush_standard_output();

}  // namespace rimu
