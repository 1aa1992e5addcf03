// What every whole-render benchmark needs besides the renderer: a description of the machine it ran on, the
// scene's pixel filter, number formatting, plots, and the replacement of its own section of docs/benchmarks.md.
// Header-only and bench-only (the benchmarks are separate executables; nothing in src/ depends on this).
#pragma once

#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "render/film/pixel_filter.h"
#include "render/scene/scene.h"
#include "spectral/io/gnuplot_process.h"

#ifndef RIMU_BENCH_BUILD
#define RIMU_BENCH_BUILD "(unknown: not built through bench/CMakeLists.txt)"
#endif

namespace rimu::bench {

/// Parses the command line with CLI11 (as the tools do): after --help prints the usage and exits 0; on a bad command
/// line prints CLI11's message and exits 1. Returns the command as typed, for the "reproduce with" line of a report.
inline std::string parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::exit(app.exit(e) == 0 ? 0 : 1);  // CLI11's own codes (105, 109, ...) → the tools' 1
  }
  std::string command;
  for (int i = 0; i < argc; ++i)
    command += i ? " " + std::string(argv[i]) : std::filesystem::path(argv[0]).filename().string();
  return command;
}

/// The CPU's model name from /proc/cpuinfo.
inline std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

/// The 1-, 5- and 15-minute load averages: how busy the machine was while the figures were taken.
inline std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

/// "<CPU model>, <n> logical cores": the machine line every report prints.
inline std::string machine_description() {
  return cpu_model() + ", " + std::to_string(std::thread::hardware_concurrency()) + " logical cores";
}

/// Compiler, build type and flags of the benchmark build (bench/CMakeLists.txt defines RIMU_BENCH_BUILD).
inline const char* build_description() { return RIMU_BENCH_BUILD; }

/// The pixel filter a scene asks for.
inline PixelFilter make_filter(const FilterSettings& f) {
  if (f.type == "box") return PixelFilter::box(f.radius_px);
  if (f.type == "blackman-harris") return PixelFilter::blackman_harris(f.radius_px);
  return PixelFilter::gaussian(f.radius_px, f.sigma_px);
}

/// printf-style formatting of one number.
inline std::string format(double v, const char* f = "%.4g") {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, f, v);
  return buffer;
}

/// Draws `job` to `png` with Rimu's plotting runner (spectral/io/gnuplot_process.h: no shell, data and script in a
/// private temporary folder); reports (does not throw) when gnuplot is missing or fails: the figures are already
/// printed and written as tables, the plot is an addition.
inline bool draw_plot(const GnuplotJob& job, const std::filesystem::path& png) {
  try {
    run_gnuplot(job, png);
    return true;
  } catch (const std::exception& e) {
    std::cerr << "plot not drawn: " << e.what() << "\n";
    return false;
  }
}

/// One point of an error-against-time curve: a render of `spp` samples per pixel that took `seconds` of wall time.
struct ErrorTimePoint {
  double seconds = 0, relative_mse = 0;
  int spp = 0;
};

/// The speed-against-error plot every such report draws: relative MSE against wall time, log-log, one line per
/// series (the map's order), titled `title`.
inline bool draw_error_time_plot(const std::string& title,
                                 const std::map<std::string, std::vector<ErrorTimePoint>>& series,
                                 const std::filesystem::path& png) {
  GnuplotJob job;
  job.terminal = "pngcairo size 640,440 noenhanced";
  std::ostringstream gp;
  gp << "set logscale xy\nset xlabel 'wall time (s)'\nset ylabel 'relative MSE vs reference'\n"
     << "set title " << gnuplot_text(title) << " noenhanced\nset key top right noenhanced\nset grid\nplot ";
  int index = 0;
  for (const auto& [name, points] : series) {
    std::ostringstream data;
    for (const ErrorTimePoint& p : points) data << p.seconds << " " << p.relative_mse << " " << p.spp << "\n";
    const std::string file = "series" + std::to_string(index) + ".dat";
    job.data_files.emplace_back(file, data.str());
    gp << (index++ ? ", " : "") << "'" << file << "' using 1:2 with linespoints title " << gnuplot_text(name);
  }
  job.commands = gp.str();
  return draw_plot(job, png);
}

/// Replaces the text between `<!-- <marker>:begin -->` and `<!-- <marker>:end -->` in `path` with `section`;
/// appends the section under `heading` when the markers are missing. The rest of the file is left alone, so
/// hand-written reading notes around a generated section survive a re-run. Written through a temporary file and
/// a rename: an interrupted benchmark never leaves a half-written document.
inline void update_docs_section(const std::filesystem::path& path, const std::string& marker,
                                const std::string& heading, const std::string& section) {
  const std::string begin = "<!-- " + marker + ":begin -->", end = "<!-- " + marker + ":end -->";
  std::string text;
  if (std::ifstream in(path); in) text.assign(std::istreambuf_iterator<char>(in), {});
  if (text.empty()) text = "# Benchmarks\n\n";
  const std::string block = begin + "\n" + section + end;
  const size_t b = text.find(begin), e = text.find(end);
  if (b != std::string::npos && e != std::string::npos && e > b)
    text.replace(b, e + end.size() - b, block);
  else
    text += "\n" + heading + "\n\n" + block + "\n";
  const std::filesystem::path temporary = path.string() + ".tmp";
  std::ofstream(temporary) << text;
  std::filesystem::rename(temporary, path);
}

}  // namespace rimu::bench
