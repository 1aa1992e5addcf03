// The `rimu merge` subcommand (merge_command.cpp).
#pragma once

/// Parses `merge PART... -o OUT` (argv[0] is "merge") and merges; returns the exit code (0, 1 bad input, 2 failure).
int run_merge_command(int argc, char** argv);
