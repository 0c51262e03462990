// The one way JSON input is read (config files, --set values, summary.json
// on --resume, mesh sidecars): bounded in size and nesting, numbers within
// double's range, and every failure a ConfigError of one printable line
// naming the source, line and column.
#pragma once

#include "config.h"

#include <cstddef>
#include <filesystem>
#include <string>

namespace piezocontact
{
/// Limits of JSON input: configs are small; nesting beyond this is an attack
/// or an accident, and unbounded nesting would exhaust the stack
inline constexpr std::size_t max_config_bytes = 1 << 20;
inline constexpr int max_json_depth = 32;
/// summary.json grows with the steps of a run (about 1 kB each)
inline constexpr std::size_t max_summary_bytes = std::size_t(1) << 30;

/// Parse `text`. Throws ConfigError "SOURCE: invalid JSON at line L column
/// C: REASON" (or the limit exceeded).
json parse_json(const std::string& text, const std::string& source,
                std::size_t max_bytes = max_config_bytes);

/// Read and parse a regular file; the OS's reason if it cannot be read.
/// Throws ConfigError naming the file.
json read_json_file(const std::filesystem::path& path,
                    std::size_t max_bytes = max_config_bytes);

/// `text` fit for a one-line message: bytes outside printable ASCII as \xNN,
/// at most `max` characters (then "...")
std::string printable(const std::string& text, std::size_t max = 160);

inline std::string printable(const char* text, std::size_t max = 160)
{
  return printable(std::string(text), max);
}

/// A JSON value fit for a one-line message (printable, abbreviated)
std::string printable(const json& value, std::size_t max = 160);
} // namespace piezocontact
