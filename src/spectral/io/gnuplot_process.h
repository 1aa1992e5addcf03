// The one way Rimu draws a plot: gnuplot run without a shell, in a private temporary folder, on text that gnuplot
// cannot expand, with the PNG installed at the user's path only when it is complete.
//
// Why it is built this way: a user's path, a file name or a spectrum's description can hold any character. Pasted
// into a shell command line, a quote runs a command; pasted into a gnuplot script, a backquote runs one too
// (gnuplot substitutes `...` in double-quoted strings and on the command line) and enhanced-text markup (^ _ @ { })
// mangles titles. So: the script and its data live in a folder made by mkdtemp (mode 0700) and refer to each
// other by fixed names; gnuplot is started with posix_spawn (an argument vector, no shell) inside that folder and
// writes a fixed name there; user text enters a script only through gnuplot_text(); the finished PNG is copied
// beside its destination under a hidden temporary name and renamed over it. The folder is removed in every case.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "spectral/error.h"

namespace rimu {

/// gnuplot is missing or failed, or the finished PNG could not be installed: a failure of the machine, not of the
/// user's input (tools exit with status 2). The message names what failed and carries gnuplot's own error output.
class PlotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The gnuplot binary Rimu runs: $RIMU_GNUPLOT if set and not empty, else /usr/bin/gnuplot (made absolute).
std::filesystem::path gnuplot_binary();

/// What to check before anything is computed or written, so that a bad plot option costs nothing and leaves
/// nothing behind: `png` names a file (not a folder) in an existing folder this process may write in (else
/// InputError at `where`), and gnuplot_binary() is an executable file (else PlotError).
void check_plot_destination(const std::filesystem::path& png, const SourceLocation& where);

/// `text` as a single-quoted gnuplot string that gnuplot prints as given: every character outside a safe set
/// (letters, digits, space, UTF-8 beyond ASCII, and _ . , : ; + - = / % # ( ) [ ] < > * ! ?) becomes '_', so no
/// quote or line break can end the string and no backquote, $ or @ can be expanded. '_' is enhanced-text markup,
/// so scripts say `noenhanced` on every title, label and key that holds such text.
std::string gnuplot_text(std::string_view text);

/// `path`'s file name, for a plot title: an absolute path says nothing to whoever reads the plot.
std::string plot_file_name(const std::filesystem::path& path);

/// One plot: gnuplot commands and the data files they read.
struct GnuplotJob {
  std::string terminal = "pngcairo size 800,500";  ///< the `set terminal` arguments (a PNG terminal)
  std::string commands;  ///< what follows `set terminal` and `set output`; data files by their names only
  /// Data files written into the private folder before gnuplot starts: name (letters, digits, '_', '-', '.';
  /// checked) and contents.
  std::vector<std::pair<std::string, std::string>> data_files;
};

/// Runs `job` and installs the PNG at `png` (replacing an existing file; on failure nothing is left at `png` or
/// in the temporary folder). Throws PlotError naming `png` with gnuplot's error output when gnuplot is missing,
/// exits with an error, or draws nothing; InputError when the destination fails check_plot_destination().
/// Cost: one gnuplot process (~0.1-0.5 s).
void run_gnuplot(const GnuplotJob& job, const std::filesystem::path& png);

}  // namespace rimu
