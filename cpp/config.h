// Run configuration: JSON file + `--set key.path=value` overrides, checked
// against config/schema.json (embedded at build time). The same rules and
// wording as demos/piezocontact/config.py.
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace piezo
{
using json = nlohmann::ordered_json;

/// A problem with the user's input; the message names file, key and value.
struct ConfigError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

constexpr int exit_config_error = 2;
constexpr int exit_run_error = 3;

/// Read, apply overrides, validate; return the effective config with the
/// schema's defaults filled in. Throws ConfigError.
json load_config(const std::string& path,
                 const std::vector<std::string>& overrides);

/// Apply overrides to a config and validate it; errors name `source`
json configure(json cfg, const std::vector<std::string>& overrides,
               const std::string& source);

/// Nearest key to a misspelt one (empty if none is close); exposed for tests.
std::string closest_key(const std::string& key,
                        const std::vector<std::string>& candidates);
} // namespace piezo
