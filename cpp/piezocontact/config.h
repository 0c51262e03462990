// The JSON layer: a config file + `--set key.path=value` overrides, checked
// against config/schema.json (embedded at build time) and the cross-key
// rules, turned into typed settings and the values of the forms' Constants.
// The one validator: the executable and the Python package both call it.
#pragma once

#include "model.h"
#include "settings.h"

#include <mpi.h>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace piezocontact
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

/// Check that every vector and matrix of a validated config has the shape
/// of d dimensions (known once the mesh is read); return it with the
/// defaults that depend on d filled in. Throws ConfigError.
json check_dimension(const json& cfg, int d, const std::string& source);

/// Throw rank 0's error (if not empty) as the same ConfigError on every
/// rank, so that none waits for the others. Collective.
void bcast_error(std::string& error, MPI_Comm comm);

/// The typed settings of a validated config (boundaries in sorted order)
RunSettings run_settings(const json& cfg);

/// Which pieces of the mesh carry which terms, from a validated config
ModelSpec model_spec(const json& cfg);

/// The contact block of a boundary's entry: its own ("contact": {...}),
/// the top-level one ("contact": true), or null (no contact)
const json* contact_block(const json& cfg, const json& boundary);

/// Whether a boundary's contact is the paper's foundation as the first
/// releases ran it: "contact": true with a top-level block that has no
/// obstacle and the penalty method (the shared "contact" piece of the
/// forms; every other contact boundary is an "obstacle" piece of its own)
bool paper_foundation(const json& cfg, const json& boundary);

/// Fill the Constants of a model from a validated config, each from the
/// key its source names (Model::sources; zero where the config gives
/// none), and the time step k = T/steps and the switches of a manufactured
/// solution. The config's boundaries and regions are the mesh's
/// (mesh.h check_names).
void set_constants(const json& cfg, const Model& model);

/// The data given by expressions (numbers that vary in space or time):
/// the fields of the model to interpolate them into (Model::data_fields,
/// load_data_fields), by piece and datum name. Their Constants stay zero.
std::vector<SpatialLoad> spatial_loads(const json& cfg, const Model& model);

/// The Constants whose config key carries a history (set_constants sets
/// their value, the time loop scales it at every step)
std::vector<TimedConstant> timed_constants(const json& cfg, const Model& model);

/// Nearest key to a misspelt one (empty if none is close); exposed for tests.
std::string closest_key(const std::string& key,
                        const std::vector<std::string>& candidates);
} // namespace piezocontactcontact
