#include "common/tool_main.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <new>
#include <sstream>

#include "spectral/error.h"
#include "spectral/version.h"

namespace rimu {

std::string tool_version_text(const std::string& tool_name) {
  return tool_name + " " + rimu_version() + " (commit " + rimu_git_commit() + ")";
}

void flush_standard_output() {
  // std::cout writes through C's stdout (sync_with_stdio is on), so an error can show in either: the stream's
  // badbit (a write the buffer could not take), stdout's error indicator (an earlier failed flush), or this flush.
  errno = 0;
  std::cout.flush();
  const bool stream_failed = std::cout.bad();
  const bool flush_failed = std::fflush(stdout) != 0;
  const int reason = errno;
  if (stream_failed || flush_failed || std::ferror(stdout))
    throw std::runtime_error(std::string("cannot write to standard output: ") +
                             (reason != 0 ? std::strerror(reason) : "write error"));
}

namespace {

// CLI11 reports --help and --version as "errors" with exit code 0; everything else it throws is a usage error.
int command_line_exit_code(const CLI::App& app, const CLI::ParseError& e, const std::string& prefix, std::ostream& err) {
  std::ostringstream usage_text;
  const int cli11_code = app.exit(e, std::cout, usage_text);
  if (cli11_code == 0) return 0;
  err << prefix << usage_text.str();
  return 1;
}

// The outcome of `step` as an exit code (0 when it returns), with the message for anything it throws.
int exit_code_of(const std::string& prefix, std::ostream& err, const std::function<int()>& step) {
  try {
    return step();
  } catch (const InputError& e) {
    err << prefix << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    err << prefix << "error: out of memory\n";
    return 2;
  } catch (const std::exception& e) {
    err << prefix << "error: " << e.what() << "\n";
    return 2;
  } catch (...) {
    err << prefix << "error: an unknown failure\n";
    return 2;
  }
}

int parse_and_run(const std::string& name, CLI::App& app, int argc, const char* const* argv,
                  const std::function<void()>& body, std::ostream& err) {
  app.set_version_flag("--version", tool_version_text(name), "print the version and git commit, then exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return command_line_exit_code(app, e, name + ": ", err);
  }
  body();
  return 0;
}

// Output that never arrived is a failure even when the tool itself succeeded.
int with_output_checked(const std::string& prefix, std::ostream& err, int code) {
  const int flush_code = exit_code_of(prefix, err, [] {
    flush_standard_output();
    return 0;
  });
  return code != 0 ? code : flush_code;
}

}  // namespace

int run_tool(const ToolInfo& tool, int argc, const char* const* argv, const std::function<void(CLI::App&)>& declare,
             const std::function<void()>& body, std::ostream& err) {
  const std::string prefix = tool.name + ": ";
  const int code = exit_code_of(prefix, err, [&] {
    CLI::App app{tool.description, tool.name};
    declare(app);
    return parse_and_run(tool.name, app, argc, argv, body, err);
  });
  return with_output_checked(prefix, err, code);
}

int run_tool(const ToolInfo& tool, int argc, const char* const* argv, const std::function<void(CLI::App&)>& declare,
             const std::function<void()>& body) {
  return run_tool(tool, argc, argv, declare, body, std::cerr);
}

int run_tool(const std::string& name, CLI::App& app, int argc, const char* const* argv,
             const std::function<void()>& body) {
  const std::string prefix = name + ": ";
  const int code = exit_code_of(prefix, std::cerr, [&] { return parse_and_run(name, app, argc, argv, body, std::cerr); });
  return with_output_checked(prefix, std::cerr, code);
}

}  // namespace rimu
