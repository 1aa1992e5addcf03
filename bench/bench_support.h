// What every whole-render benchmark needs besides the renderer: a description of the machine it ran on, the
// scene's pixel filter, number formatting, plots, and the replacement of its own section of docs/benchmarks.md.
// Header-only and bench-only (the benchmarks are separate executables; nothing in src/ depends on this).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <thread>

#include "render/pixel_filter.h"
#include "render/scene/scene.h"
#include "spectral/gnuplot_process.h"

#ifndef RIMU_BENCH_BUILD
#define RIMU_BENCH_BUILD "(unknown: not built through bench/CMakeLists.txt)"
#endif

namespace rimu::bench {

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

/// Draws `job` to `png` with Rimu's plotting runner (spectral/gnuplot_process.h: no shell, data and script in a
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
