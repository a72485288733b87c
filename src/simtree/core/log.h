#pragma once
// Logging goes through spdlog's default logger (stderr). This sets it up once for the CLI and
// tests: a level by name and a short pattern.

#include <string>

namespace simtree {

// `level` is one of trace, debug, info, warn, error, off; throws InputError otherwise.
void ConfigureLogging(const std::string& level);

}  // namespace simtree
