#include "dynamics.h"
#include "diagnostics.h"
#include "harmonic.h"
#include "linear_solver.h"
#include "linearisation.h"
#include "modal.h"
#include "output.h"
#include "output_mesh.h"

#include <chrono>
#include <cmath>
#include <complex>
#include <dolfinx/io/XDMFFile.h>
#include <numbers>

namespace piezocontact
{
namespace fs = std::filesystem;
using namespace dolfinx;
using Complex = std::complex<double>;

namespace
{
int rank_of(MPI_Comm comm)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}

json complex_json(Complex z) { return json::array({z.real(), z.imag()}); }

/// problem.x <- owned entries (ghosts updated), and its u and phi
void set_state(Problem& p, const std::vector<double>& owned)
{
  auto x = compat::mutable_values(*p.x->x());
  std::copy(owned.begin(), owned.end(), x.begin());
  p.x->x()->scatter_fwd();
  p.update_fields();
}

/// One XDMF file of frames, each some fields at a "time" (a mode's number,
/// a frequency): `frame(i)` sets the fields and returns their time
void write_frames(Problem& p, const fs::path& xdmf, int count,
                  const std::vector<std::shared_ptr<fem::Function<double>>>& fields,
                  const std::function<double(int)>& frame)
{
  const std::size_t vertices = compat::topology(*p.mesh).dim() + 1;
  const bool refine = p.V_u->dofmap()->cell_dofs(0).size() > vertices;
  OutputMesh out(p.mesh, refine);
  std::string error;
  try
  {
    io::XDMFFile file(p.comm, xdmf, "w");
    file.write_mesh(*out.mesh());
    for (int i = 0; i < count; ++i)
    {
      const double t = frame(i);
      for (const auto& f : fields)
        file.write_function(out(*f), t, "/Xdmf/Domain");
    }
    file.close();
  }
  catch (const std::exception& e)
  {
    error = e.what();
  }
  int failed = !error.empty();
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_LOR, p.comm);
  if (failed)
    throw OutputError("cannot write " + xdmf.string() + ": "
                      + (error.empty() ? "failed on another rank" : error));
}

json modal(Problem& p, const RunSettings& s, const fs::path& dir, json summary,
           const Linearisation& lin)
{
  ModalCost cost;
  const auto t0 = std::chrono::steady_clock::now();
  const auto modes = natural_modes(lin, s.analysis, &cost);
  summary["analysis_timing"] = {
      {"factorisation_s", cost.factorisation_s},
      {"eigensolver_s", cost.eigensolver_s},
      {"solves", cost.solves},
      {"one_solve_s", cost.solve_s},
      {"factor_entries", cost.factor_entries},
      {"pencil", cost.hermitian ? "hermitian" : "condensed"},
      {"total_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()}};
  json list = json::array();
  const std::size_t n = modes.empty() ? 0 : modes[0].x.size();
  std::vector<double> r(n);
  for (const auto& m : modes)
  {
    Vec x, Kx;
    MatCreateVecs(lin.K().mat(), &x, &Kx);
    PetscScalar* xv;
    VecGetArray(x, &xv);
    std::copy(m.x.begin(), m.x.end(), xv);
    VecRestoreArray(x, &xv);
    MatMult(lin.K().mat(), x, Kx);
    const PetscScalar* kv;
    VecGetArrayRead(Kx, &kv);
    std::copy(kv, kv + n, r.begin());
    VecRestoreArrayRead(Kx, &kv);
    VecDestroy(&x);
    VecDestroy(&Kx);
    const auto Q = p.reaction_charges(r);
    const auto V = p.electrode_potentials(m.x);
    json electrodes = json::object();
    for (std::size_t e = 0; e < p.electrodes.size(); ++e)
      electrodes[p.electrodes[e].name] = {{"charge", Q[e]}, {"potential", V[e]}};
    list.push_back({{"frequency", m.frequency},
                    {"eigenvalue", m.eigenvalue},
                    {"error", m.error},
                    {"electrodes", electrodes}});
  }
  summary["modes"] = list;
  if (s.output.xdmf and !modes.empty() and !dir.empty())
    write_frames(p, dir / "modes.xdmf", int(modes.size()), {p.u, p.phi},
                 [&](int i)
                 {
                   set_state(p, modes[i].x);
                   return double(i + 1);
                 });
  if (int(modes.size()) < s.analysis.modes)
  {
    summary["status"] = "failed";
    summary["error"] = "the eigensolver converged " + std::to_string(modes.size()) + " of the "
                       + std::to_string(s.analysis.modes) + " modes asked for (the model has "
                       + std::to_string(cost.dofs_with_mass) + " dofs with mass)";
  }
  return summary;
}

/// The amplitude of each electrode's prescribed potential (0: grounded or
/// floating)
std::vector<double> driven_potentials(Problem& p)
{
  auto x = compat::mutable_values(*p.x->x());
  const std::vector<double> saved(x.begin(), x.end());
  std::fill(x.begin(), x.end(), 0.0);
  for (const auto& e : p.electrodes)
    if (!e.floating)
      compat::set_bc_values(*e.bc, x);
  auto V = p.electrode_potentials(std::span<const double>(x.data(), x.size()));
  std::copy(saved.begin(), saved.end(), x.begin());
  return V;
}

/// Each electrode's charge, current, potential and (driven) admittance
json electrodes_json(const Problem& p, const HarmonicResponse& h,
                     const std::vector<double>& driven)
{
  const double w = 2 * std::numbers::pi * h.frequency;
  const auto Qr = p.reaction_charges(h.residual_re), Qi = p.reaction_charges(h.residual_im);
  const auto Vr = p.electrode_potentials(h.re), Vi = p.electrode_potentials(h.im);
  json out = json::object();
  for (std::size_t e = 0; e < p.electrodes.size(); ++e)
  {
    const Complex Q(Qr[e], Qi[e]), I = Complex(0.0, w) * Q;
    json entry = {{"charge", complex_json(Q)}, {"current", complex_json(I)},
                  {"potential", complex_json({Vr[e], Vi[e]})}};
    // the circuit's admittance: the current the source drives into the
    // electrode, -I (charge is int D.nu, minus the free charge), over V
    if (!p.electrodes[e].floating and driven[e] != 0.0)
      entry["admittance"] = complex_json(-I / driven[e]);
    out[p.electrodes[e].name] = entry;
  }
  return out;
}

/// The probes' complex u and phi
json probes_json(Problem& p, const Probes& probes, const HarmonicResponse& h)
{
  set_state(p, h.re);
  const auto re = probes.evaluate(p);
  set_state(p, h.im);
  const auto im = probes.evaluate(p);
  const std::size_t d = p.dim();
  json out = json::array();
  for (std::size_t i = 0; i < probes.points.size(); ++i)
  {
    json u = json::array();
    for (std::size_t c = 0; c < d; ++c)
      u.push_back(complex_json({re[i][c], im[i][c]}));
    out.push_back(
        {{"point", std::vector<double>(probes.points[i].begin(), probes.points[i].begin() + d)},
         {"u", u},
         {"phi", complex_json({re[i][d], im[i][d]})}});
  }
  return out;
}

json harmonic_timing(const std::vector<HarmonicResponse>& responses)
{
  json out = {{"assembly_s", json::array()}, {"factorisation_s", json::array()},
              {"solve_s", json::array()}};
  for (const auto& h : responses)
  {
    out["assembly_s"].push_back(h.assembly_s);
    out["factorisation_s"].push_back(h.factorisation_s);
    out["solve_s"].push_back(h.solve_s);
  }
  return out;
}

/// harmonic.xdmf: u and phi, real and imaginary parts, at "time" = f
void write_responses(Problem& p, const fs::path& xdmf,
                     const std::vector<HarmonicResponse>& responses)
{
  std::vector<std::shared_ptr<fem::Function<double>>> fields;
  for (const auto& [V, name] : {std::pair{p.V_u, "u_re"}, std::pair{p.V_u, "u_im"},
                               std::pair{p.V_phi, "phi_re"}, std::pair{p.V_phi, "phi_im"}})
  {
    fields.push_back(std::make_shared<fem::Function<double>>(V));
    fields.back()->name = name;
  }
  write_frames(p, xdmf, int(responses.size()), fields,
               [&](int i)
               {
                 for (int part = 0; part < 2; ++part)
                 {
                   set_state(p, part == 0 ? responses[i].re : responses[i].im);
                   std::ranges::copy(compat::values(*p.u->x()),
                                     compat::mutable_values(*fields[part]->x()).begin());
                   std::ranges::copy(compat::values(*p.phi->x()),
                                     compat::mutable_values(*fields[2 + part]->x()).begin());
                 }
                 return responses[i].frequency;
               });
}

json harmonic(Problem& p, const RunSettings& s, const fs::path& dir, json summary,
              const Linearisation& lin, const std::string& source)
{
  HarmonicSolver solver(p, lin, source);
  const Probes probes(p, s.probes, source);
  const auto driven = driven_potentials(p);
  std::vector<HarmonicResponse> responses;
  json list = json::array();
  for (double f : s.analysis.frequencies)
  {
    try
    {
      responses.push_back(solver.solve(f));
    }
    catch (const LinearSolveFailure& e) // singular: one line, exit 3, not a crash
    {
      throw AnalysisFailure(e.what());
    }
    const auto& h = responses.back();
    list.push_back({{"frequency", f},
                    {"electrodes", electrodes_json(p, h, driven)},
                    {"probes", probes_json(p, probes, h)}});
  }
  summary["harmonic"] = list;
  summary["analysis_timing"] = harmonic_timing(responses);
  if (s.output.xdmf and !dir.empty())
    write_responses(p, dir / "harmonic.xdmf", responses);
  return summary;
}
} // namespace

json analyse(Problem& p, const RunSettings& s, const fs::path& dir, json summary,
             const std::string& source)
{
  const auto t0 = std::chrono::steady_clock::now();
  const Linearisation lin(p);
  const double linearisation_s
      = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  summary["analysis_state"] = s.analysis.at_end ? "end" : "start";
  summary = s.analysis.kind == AnalysisSettings::Kind::modal
                ? modal(p, s, dir, summary, lin)
                : harmonic(p, s, dir, summary, lin, source);
  summary["analysis_timing"]["linearisation_s"] = linearisation_s;
  summary["dofs"] = p.W->dofmap()->index_map->size_global() * p.W->dofmap()->index_map_bs();
  if (!summary.contains("status") or summary["status"] != "failed")
    summary["status"] = "completed";
  if (!dir.empty()) // else in memory
    collectively(p.comm, rank_of(p.comm) == 0,
                 [&] { write_json_atomic(dir / "summary.json", summary); });
  if (summary["status"] == "failed")
    throw AnalysisFailure(summary["error"].get<std::string>());
  return summary;
}
} // namespace piezocontact
