#include "spectral/io/gnuplot_process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "spectral/io/output_file.h"

extern char** environ;

namespace rimu {
namespace {

// Fixed names inside the private folder: nothing the user typed ever names a file gnuplot opens.
constexpr const char* kScriptName = "plot.gp";
constexpr const char* kImageName = "plot.png";
constexpr const char* kOutputName = "gnuplot-output.txt";

bool is_safe_data_name(const std::string& name) {
  if (name.empty() || name == kScriptName || name == kImageName || name == kOutputName || name[0] == '.') return false;
  for (const char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return true;
}

// A folder only this process can read, made by mkdtemp under $TMPDIR (or /tmp) and removed with everything in it
// when the plot is done, whether it succeeded or threw.
class PrivateFolder {
 public:
  PrivateFolder() {
    std::error_code error;
    std::filesystem::path base = std::filesystem::temp_directory_path(error);
    if (error) throw PlotError("cannot plot: no temporary folder ($TMPDIR or /tmp): " + error.message());
    std::string pattern = (base / "rimu-plot-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr)  // mode 0700
      throw PlotError("cannot plot: cannot create a private temporary folder in '" + base.string() +
                      "': " + std::strerror(errno));
    path_ = pattern;
  }
  ~PrivateFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  PrivateFolder(const PrivateFolder&) = delete;
  PrivateFolder& operator=(const PrivateFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

void write_file(const std::filesystem::path& path, const std::string& contents) {
  std::ofstream out(path, std::ios::binary);
  if (!(out << contents) || !(out.flush()))
    throw PlotError("cannot plot: cannot write the temporary file '" + path.string() + "'");
}

std::string read_text(const std::filesystem::path& path, size_t max_chars) {
  std::ifstream in(path, std::ios::binary);
  std::string text(std::istreambuf_iterator<char>(in), {});
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  if (text.size() > max_chars) text = text.substr(0, max_chars) + " [...]";
  return text;
}

// Runs `binary script` inside `folder` (no shell: posix_spawn with an argument vector), standard input from
// /dev/null, standard output and error into `output`. Returns the wait status.
int spawn_and_wait(const std::filesystem::path& binary, const std::filesystem::path& folder,
                   const std::filesystem::path& output) {
  posix_spawn_file_actions_t actions;
  if (const int e = posix_spawn_file_actions_init(&actions); e != 0)
    throw PlotError("cannot plot: cannot prepare the gnuplot process: " + std::string(std::strerror(e)));
  // Each action returns 0 or an errno value; the first failure is kept.
  int setup_error = posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  if (!setup_error)
    setup_error = posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output.c_str(),
                                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (!setup_error) setup_error = posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  if (!setup_error) setup_error = posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
  std::string program = binary.string(), script = kScriptName;
  char* argv[] = {program.data(), script.data(), nullptr};
  pid_t pid = 0;
  const int spawn_error =
      setup_error ? setup_error : posix_spawn(&pid, program.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_error != 0)
    throw PlotError("cannot plot: cannot start gnuplot (" + program + "): " + std::strerror(spawn_error));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw PlotError("cannot plot: lost the gnuplot process: " + std::string(std::strerror(errno)));
  return status;
}

// Installs the finished image at `destination` through the output-file code every tool uses (output_file.h): a
// hidden temporary beside it renamed over it, or, for a destination that is a device, FIFO or link, a checked copy
// into it (the device stays a device; a full one is an OutputError). A reader never sees a half-written PNG.
void install(const std::filesystem::path& image, const std::filesystem::path& destination) {
  write_atomically(destination, [&](const std::filesystem::path& temporary) {
    std::error_code error;
    std::filesystem::copy_file(image, temporary, std::filesystem::copy_options::overwrite_existing, error);
    if (error) throw std::runtime_error(error.message());
  });
}

}  // namespace

std::filesystem::path gnuplot_binary() {
  const char* env = std::getenv("RIMU_GNUPLOT");
  const std::filesystem::path binary = env && *env ? std::filesystem::path(env) : "/usr/bin/gnuplot";
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(binary, error);
  return error ? binary : absolute;
}

void check_plot_destination(const std::filesystem::path& png, const SourceLocation& where) {
  if (png.empty() || !png.has_filename())
    throw InputError(where, "the plot path '" + png.string() + "' names no file");
  const std::filesystem::path folder = folder_of(png);
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error))
    throw InputError(where, "cannot write the plot '" + png.string() + "': the folder '" + folder.string() +
                                "' does not exist");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw InputError(where, "cannot write the plot '" + png.string() + "': the folder '" + folder.string() +
                                "' is not writable");
  if (std::filesystem::is_directory(png, error))
    throw InputError(where, "cannot write the plot '" + png.string() + "': it is a folder");
  // The format follows the name, as for the renderer's images: gnuplot draws PNG, so a .jpg (or a device named
  // without an extension) would get PNG bytes under another format's name.
  if (lower_case_extension(png) != "png")
    throw InputError(where, "cannot write the plot '" + png.string() + "': plots are PNG images, so the name must end "
                            "in .png (got '" + png.extension().string() + "')");
  check_output_path(png);  // as every output: a device or FIFO must be writable, the folder must take a file
  const std::filesystem::path binary = gnuplot_binary();
  if (!std::filesystem::is_regular_file(binary, error) || ::access(binary.c_str(), X_OK) != 0)
    throw PlotError("cannot plot '" + png.string() + "': gnuplot not found at " + binary.string() +
                    " (install gnuplot, or set RIMU_GNUPLOT to its path)");
}

std::string gnuplot_text(std::string_view text) {
  static constexpr std::string_view kSafePunctuation = " _.,:;+-=/%#()[]<>*!?";
  std::string out = "'";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    const bool safe = std::isalnum(byte) || byte >= 0x80 || kSafePunctuation.find(c) != std::string_view::npos;
    out += safe ? c : '_';
  }
  return out + "'";
}

std::string plot_file_name(const std::filesystem::path& path) { return path.filename().string(); }

void run_gnuplot(const GnuplotJob& job, const std::filesystem::path& png) {
  check_plot_destination(png, {});
  const std::filesystem::path binary = gnuplot_binary();
  const PrivateFolder folder;
  for (const auto& [name, contents] : job.data_files) {
    if (!is_safe_data_name(name)) throw PlotError("internal error: unsafe plot data file name '" + name + "'");
    write_file(folder.path() / name, contents);
  }
  // The terminal and output first, with the fixed image name; `unset output` closes the PNG before gnuplot exits.
  write_file(folder.path() / kScriptName, "set terminal " + job.terminal + "\nset output '" + kImageName + "'\n" +
                                              job.commands + "\nunset output\n");
  const std::filesystem::path output = folder.path() / kOutputName, image = folder.path() / kImageName;
  const int status = spawn_and_wait(binary, folder.path(), output);
  std::string failure;
  if (WIFSIGNALED(status))
    failure = "killed by signal " + std::to_string(WTERMSIG(status));
  else if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
    failure = "could not be run (exit status 127)";
  else if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
    failure = "exited with status " + std::to_string(WEXITSTATUS(status));
  else {
    std::error_code error;
    const auto size = std::filesystem::file_size(image, error);
    if (error || size == 0) failure = "drew nothing";
  }
  if (!failure.empty()) {
    const std::string said = read_text(output, 4000);
    throw PlotError("gnuplot (" + binary.string() + ") " + failure + " drawing '" + png.string() + "'" +
                    (said.empty() ? std::string(" and printed nothing") : ":\n" + said));
  }
  install(image, png);
}

}  // namespace rimu
