// The `rimu denoise` subcommand (denoise_command.cpp).
#pragma once

/// Parses `denoise IN.exr -o OUT.exr` (argv[0] is "denoise") and denoises; returns the exit code (0, 1 bad input,
/// 2 failure).
int run_denoise_command(int argc, char** argv);
