// The main() wrapper every tool shares (tools/common/tool_main.h): each outcome of a tool becomes the documented
// exit code with a message, and nothing escapes as an uncaught exception (which would abort with 134).
#include <doctest/doctest.h>

#include <new>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "common/tool_main.h"
#include "spectral/error.h"
#include "spectral/version.h"

namespace {

// Runs a tool named "t" with one option --n and the given body on `args`; returns the exit code and the messages.
struct Outcome {
  int code = -1;
  std::string messages;
};
Outcome run(std::vector<const char*> args, const std::function<void()>& body) {
  args.insert(args.begin(), "t");
  std::ostringstream err;
  int n = 0;
  Outcome o;
  o.code = rimu::run_tool({"t", "a test tool"}, int(args.size()), args.data(),
                          [&](CLI::App& app) { app.add_option("--n", n, "a number"); }, body, err);
  o.messages = err.str();
  return o;
}

}  // namespace

TEST_CASE("tool main: success, bad input and failures map to exit codes 0, 1 and 2 with the tool's name") {
  CHECK(run({}, [] {}).code == 0);
  const Outcome input = run({}, [] { throw rimu::InputError({"lamp.csv", 3, ""}, "expected a number"); });
  CHECK(input.code == 1);
  CHECK(input.messages == "t: lamp.csv:3: expected a number\n");
  const Outcome failure = run({}, [] { throw std::runtime_error("gnuplot failed"); });
  CHECK(failure.code == 2);
  CHECK(failure.messages == "t: error: gnuplot failed\n");
  const Outcome memory = run({}, [] { throw std::bad_alloc(); });
  CHECK(memory.code == 2);
  CHECK(memory.messages == "t: error: out of memory\n");
  const Outcome odd = run({}, [] { throw 42; });
  CHECK(odd.code == 2);
  CHECK(odd.messages.find("t: error:") == 0);
}

TEST_CASE("tool main: command-line errors exit 1 (not CLI11's own codes), help and version exit 0") {
  bool ran = false;
  const auto body = [&] { ran = true; };
  const Outcome unknown = run({"--bogus"}, body);
  CHECK(unknown.code == 1);
  CHECK(unknown.messages.find("t: ") == 0);
  CHECK(unknown.messages.find("--bogus") != std::string::npos);
  CHECK(run({"--n", "many"}, body).code == 1);  // CLI11's ConversionError is 106 on its own
  CHECK(run({"--n"}, body).code == 1);          // ArgumentMismatch
  CHECK_FALSE(ran);
  CHECK(run({"--help"}, body).code == 0);
  CHECK(run({"--version"}, body).code == 0);
  CHECK_FALSE(ran);  // neither runs the tool, so neither needs its data
  CHECK(run({"--n", "3"}, body).code == 0);
  CHECK(ran);
}

TEST_CASE("tool main: --version names the version and the git commit") {
  const std::string text = rimu::tool_version_text("rimu-light");
  CHECK(text == std::string("rimu-light ") + rimu::rimu_version() + " (commit " + rimu::rimu_git_commit() + ")");
  CHECK(std::string(rimu::rimu_git_commit()).size() >= 7);  // an abbreviated hash, or "unknown"
}
