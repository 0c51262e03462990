#include "record.h"

#include <cmath>
#include <cstdio>
#include <numeric>
#include <optional>

namespace piezocontact
{
namespace
{
int rank_of(MPI_Comm comm)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  return rank;
}

/// Run `action`, adding its wall time to `s`
template <typename F>
void timed(OperationStats& s, const std::string& task, F&& action)
{
  ScopedTimer timer(s, task);
  action();
}

json fields_json(const std::map<std::string, FieldNorms>& norms, double FieldNorms::*member)
{
  json out = json::object();
  for (const char* f : {"u", "phi", "charge"})
  {
    if (std::string(f) == "charge" and !norms.contains(f))
      continue; // only with floating electrodes
    if (!norms.contains(f))
    {
      out[f] = nullptr;
      continue;
    }
    const double v = norms.at(f).*member;
    out[f] = std::isnan(v) ? json(nullptr) : json(v); // undefined while x_f = 0
  }
  return out;
}

std::string numbered(const char* format, int n)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, n);
  return buf;
}

void print_progress(const std::string& label, int n, const json& step)
{
  const json& r = step["relative_residuals"];
  auto e = [](const json& v, int digits, const char* missing)
  {
    if (v.is_null())
      return std::string(missing);
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.*e", digits, v.get<double>());
    return std::string(buf);
  };
  std::printf("[%s] step %4d  t = %.4g  newton %d  rel. residual u %s phi %s"
              "  max(u.nu - g) = %s\n",
              label.c_str(), n, step["t"].get<double>(), step["newton_iterations"].get<int>(),
              e(r["u"], 1, "undefined").c_str(), e(r["phi"], 1, "undefined").c_str(),
              e(step["max_penetration"], 3, "n/a").c_str());
  std::fflush(stdout);
}
} // namespace

Record::Record(Problem& problem, const RunSettings& settings, std::filesystem::path dir,
               json summary, bool resume, bool progress, StepObserver observer)
    : _problem(problem), _rtol(settings.newton.rtol), _dir(std::move(dir)), _progress(progress),
      _observer(std::move(observer)), _label(summary.value("solver", "cpp")),
      _probes(problem, settings.probes, summary.value("config_file", "config")),
      _contact(problem, problem.model.contact_facets), _obstacles(problem),
      _state_file(problem)
{
  int size;
  MPI_Comm_size(problem.comm, &size);
  if (resume)
  {
    _summary = std::move(summary);
    _state = StepState::from_json(_summary["checkpoint"]);
    // What came after the checkpoint is done again
    auto& steps = _summary["steps"];
    steps.erase(steps.begin() + _state.step, steps.end());
    auto& events = _summary["events"];
    events.erase(events.begin() + _state.events, events.end());
    _summary.erase("error");
    _summary.erase("signal");
    if (!_summary.contains("resumed"))
      _summary["resumed"] = json::array();
    _summary["resumed"].push_back({{"step", _state.step}, {"t", _state.t}, {"mpi_size", size}});
    _summary["mpi_size"] = size;
  }
  else
  {
    const auto& imap = *problem.W->dofmap()->index_map;
    const int bs = problem.W->dofmap()->index_map_bs();
    _summary = {{"solver", _label}, {"dofs", imap.size_global() * bs}, {"mpi_size", size}};
    for (auto& [key, value] : summary.items())
      _summary[key] = value;
    _summary["steps"] = json::array();
    _summary["events"] = json::array();
    _summary["timing"] = json::object();
  }
  _summary["status"] = "running";
  try
  {
    if (!in_memory())
      _writer.emplace(problem, settings.output, _dir,
                      resume ? std::optional<int>(_state.step) : std::nullopt);
  }
  catch (const OutputError& e)
  {
    fail_on_output(e);
  }
}

Record::~Record() = default;

void Record::read_states(const States& states) const
{
  try
  {
    _state_file.read(_dir / _state.file, states);
  }
  catch (const std::runtime_error& e)
  {
    throw ConfigError(std::string("cannot resume: ") + e.what());
  }
}

void Record::write_summary()
{
  if (in_memory())
    return;
  timed(_summaries, "summary",
        [&]
        {
          collectively(_problem.comm, rank_of(_problem.comm) == 0,
                       [&] { write_json_atomic(_dir / "summary.json", _summary); });
        });
}

// A write error ends the run; the summary says so if it can still be written
void Record::mark_failed(const std::string& error)
{
  _summary["status"] = "failed";
  _summary["error"] = error;
  try
  {
    write_summary();
  }
  catch (const OutputError&) // the error already being reported says why
  {
  }
}

void Record::fail_on_output(const OutputError& e)
{
  mark_failed(e.what());
  throw e;
}

StepState Record::write_checkpoint(StepState s, const StateViews& states)
{
  s.events = _summary["events"].size();
  if (in_memory())
    return s;
  s.file = "checkpoint/" + numbered("state_%06d.npy", s.step);
  if (rank_of(_problem.comm) == 0)
    std::filesystem::create_directories(_dir / "checkpoint");
  timed(_checkpoints, "checkpoint", [&] { _state_file.write(_dir / s.file, states); });
  return s;
}

void Record::begin(const StepState& state, const StateViews& states)
{
  try
  {
    if (_state.file.empty())
      _state = write_checkpoint(state, states);
    _summary["checkpoint"] = _state.to_json();
    write_summary();
  }
  catch (const OutputError& e)
  {
    fail_on_output(e);
  }
}

json Record::accept(StepState state, const SolveReport& report, const StateViews& states,
                    bool final, const json& timing)
{
  Problem& problem = _problem;
  // what the step's record costs beside its files (probes, functionals,
  // reactions, balance, charges): "diagnostics" in the summary's timing
  std::optional<ScopedTimer> diagnostics(std::in_place, _diagnostics, "diagnostics");
  problem.update_fields();
  json step = json::object();
  step["t"] = report.t;
  step["newton_iterations"] = report.newton_iterations;
  step["factorisations"] = report.factorisations;
  const std::map<std::string, FieldNorms> none;
  const auto& last = report.history.empty() ? none : report.history.back();
  step["residual_norms"] = fields_json(last, &FieldNorms::residual);
  step["relative_residuals"] = fields_json(last, &FieldNorms::relative);
  step["relative_updates"] = fields_json(last, &FieldNorms::update);
  step["residual_history"] = json::array();
  for (const auto& h : report.history)
    step["residual_history"].push_back(fields_json(h, &FieldNorms::relative));
  step["probes"] = json::array();
  const auto values = _probes.evaluate(problem);
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const std::size_t d = problem.dim();
    step["probes"].push_back(
        {{"point", std::vector<double>(_probes.points[i].begin(), _probes.points[i].begin() + d)},
         {"u", std::vector<double>(values[i].begin(), values[i].begin() + d)},
         {"phi", values[i][d]}});
  }
  step["contact_force"] = contact_force(problem);
  if (!problem.model.spring_force.empty())
    step["spring_force"] = spring_forces(problem);
  const auto g = problem.model.data_fields.find("g"); // a gap given by expressions
  auto gap = _contact.max_normal_gap(problem, problem.model.constants.at("g")->value[0],
                                     g == problem.model.data_fields.end() ? nullptr
                                                                          : g->second.get());
  const std::string measure = problem.dim() == 2 ? "contact_length" : "contact_area";
  if (!problem.model.obstacles.empty())
    step["contacts"] = json::object();
  for (const auto& [name, _] : problem.model.obstacles)
  {
    const auto r = _obstacles.largest(problem, name);
    if (r and (!gap or *r > *gap))
      gap = r;
    step["contacts"][name] = {{"force", obstacle_force(problem, name)},
                              {measure, obstacle_contact_measure(problem, name)},
                              {"max_pressure", problem.obstacle_max_pressure(name)},
                              {"max_penetration", r ? json(*r) : json(nullptr)}};
  }
  step["max_penetration"] = gap ? json(*gap) : json(nullptr);
  double in_contact = problem.update_contact_pressure();
  for (const auto& [name, _] : problem.model.obstacles)
    in_contact += step["contacts"][name][measure].get<double>();
  if (problem.contact_pressure)
    step[measure] = in_contact;
  // the unconstrained residual at x_n: reactions, balance, electrode charges
  std::optional<dolfinx::la::Vector<double>> assembled;
  std::span<const double> r;
  if (report.residual)
    r = *report.residual;
  else // collective: every rank alike (the engine decides, not the data)
  {
    assembled.emplace(problem.assemble(problem.model.F));
    r = compat::values(*assembled).subspan(
        0, problem.W->dofmap()->index_map->size_local() * problem.W->dofmap()->index_map_bs());
  }
  step["reactions"] = json::object();
  for (const auto& [name, f] : problem.reactions(r))
    step["reactions"][name] = f;
  if (!problem.electrodes.empty())
    step["electrodes"] = electrodes_json(r, report.k);
  const ForceBalance balance = problem.force_balance(r);
  // the size of what the supports carry: a reaction's round-off is of it
  step["support_force"] = balance.supported;
  check_acceptance(step, report.acceptance, balance);
  step["krylov_iterations"] = report.krylov_iterations;
  step["k"] = report.k;
  if (!problem.model.squared_errors.empty())
    step["errors"] = problem.errors();

  // Step files, then its checkpoint, then the summary that points to both:
  // a kill at any instant leaves a summary whose every step is on disk
  const StepState previous = _state;
  diagnostics.reset();
  try
  {
    if (_writer)
      timed(_step_files, "step files",
            [&] { _writer->write_step(state.step, report.t, final); });
    _state = write_checkpoint(state, states);
    _summary["steps"].push_back(step);
    _summary["checkpoint"] = _state.to_json();
    _summary["status"] = final ? "completed" : "running";
    _summary["timing"] = timing;
    _summary["timing"]["output_s"]
        = _step_files.seconds + _checkpoints.seconds + _summaries.seconds;
    _summary["timing"]["output"] = output_timing();
    _summary["timing"]["diagnostics"] = _diagnostics.to_json();
    write_summary();
  }
  catch (const OutputError& e)
  {
    if (_summary["steps"].size() > std::size_t(previous.step))
      _summary["steps"].erase(_summary["steps"].end() - 1);
    _summary["checkpoint"] = previous.to_json();
    if (rank_of(problem.comm) == 0 and _state.file != previous.file)
    {
      // unreferenced: its space may let the summary say what went wrong
      std::error_code ec;
      std::filesystem::remove(_dir / _state.file, ec);
    }
    _state = previous;
    fail_on_output(e);
  }
  if (rank_of(problem.comm) == 0)
  {
    std::error_code ec;
    if (!previous.file.empty())
      std::filesystem::remove(_dir / previous.file, ec);
    if (_progress)
      print_progress(_label, state.step, step);
  }
  if (_observer)
    _observer(state.step, step);
  return step;
}

// Newton's test is on the Jacobi-scaled residual: where one block of the
// matrix dwarfs the rest (a contact penalty 1e19 times the elastic
// stiffness), it can pass while forces in newtons are left over. A step is
// accepted only if the loads, the contact force and the reactions balance.
void Record::check_acceptance(const json& step, Acceptance acceptance,
                              const ForceBalance& balance)
{
  acceptance.imbalance = force_imbalance(_problem, balance);
  const std::string broken = broken_rule(acceptance, _rtol, _problem);
  if (!broken.empty())
    fail("the step at t = " + json(step["t"]).dump()
         + " was accepted by its loop but breaks the acceptance rule: " + broken);
}

// The current is the backward-Euler rate of the charge, from the last
// recorded step's (the initial state, u = 0 and phi = 0, holds none)
json Record::electrodes_json(std::span<const double> r, double k) const
{
  const auto& x = *_problem.x->x();
  const auto potentials = _problem.electrode_potentials(
      compat::values(x).subspan(0, compat::index_map(x)->size_local() * x.bs()));
  const auto charges = _problem.electrode_charges();
  const auto reaction = _problem.reaction_charges(r);
  const json& steps = _summary["steps"];
  json out = json::object();
  for (std::size_t e = 0; e < _problem.electrodes.size(); ++e)
  {
    const std::string& name = _problem.electrodes[e].name;
    double before = 0.0;
    if (!steps.empty() and steps.back().contains("electrodes"))
      before = steps.back()["electrodes"][name]["charge"].get<double>();
    out[name] = {{"potential", potentials[e]},
                 {"charge", charges[e]},
                 {"reaction_charge", reaction[e]},
                 {"current", (charges[e] - before) / k}};
  }
  return out;
}

void Record::reject(const SolveReport& report, const std::string& action)
{
  const std::map<std::string, FieldNorms> none;
  const auto& last = report.history.empty() ? none : report.history.back();
  _summary["events"].push_back({{"t", report.t},
                                {"k", report.k},
                                {"newton_iterations", report.newton_iterations},
                                {"relative_residuals", fields_json(last, &FieldNorms::relative)},
                                {"relative_updates", fields_json(last, &FieldNorms::update)},
                                {"action", action}});
}

std::size_t Record::events() const { return _summary["events"].size(); }

void Record::fail(const std::string& error)
{
  mark_failed(error);
  throw NewtonFailure(error);
}

void Record::refuse(const std::string& error)
{
  mark_failed(error);
  throw ConfigError(error);
}

void Record::interrupt(int signum, const json& timing)
{
  _summary["status"] = "interrupted";
  _summary["signal"] = signal_name(signum);
  _summary["timing"] = timing;
  _summary["timing"]["output_s"] = _step_files.seconds + _checkpoints.seconds + _summaries.seconds;
  _summary["timing"]["output"] = output_timing();
  _summary["timing"]["diagnostics"] = _diagnostics.to_json();
  try
  {
    write_summary();
  }
  catch (const OutputError& e)
  {
    fail_on_output(e);
  }
  throw Interrupted(signum, _state.step, _state.t);
}

json Record::output_timing() const
{
  return {{"step_files", _step_files.to_json()},
          {"checkpoint", _checkpoints.to_json()},
          {"summary", _summaries.to_json()}};
}
} // namespace piezocontact
