// The `rimu display` subcommand (display_command.cpp).
#pragma once

/// Parses `display IN.exr --png OUT.png [...]` (argv[0] is "display") and writes the display image; returns the exit
/// code (0, 1 bad input, 2 failure).
int run_display_command(int argc, char** argv);
