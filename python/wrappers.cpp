// piezocontact.cpp: Python bindings of libpiezocontact. dolfinx objects
// cross as dolfinx's own types (its Python module registers them); JSON
// crosses as text (the Python package loads and dumps it). Written once for
// pybind11 (dolfinx 0.5) and nanobind (0.9): see bindings.h.
#include "bindings.h"

#include <caster_mpi.h>
#include <dolfinx/fem/DirichletBC.h>
#include <piezocontact/config.h>
#include <piezocontact/diagnostics.h>
#include <piezocontact/driver.h>
#include <piezocontact/mesh.h>
#include <piezocontact/output.h>
#include <piezocontact/record.h>

using namespace piezocontact;
using namespace piezocontact::bindings;
using dolfinx_wrappers::MPICommWrapper;

namespace
{
/// The mesh tools of the Python front end (mesh_tools.py)
using PyMeshConverter = std::function<int(const MeshConversion&)>;
/// A model factory written in Python: (NamedMesh, ModelSpec) -> Model
using PyModelFactory = std::function<Model(const NamedMesh&, const ModelSpec&)>;
/// A time loop written in Python: (Problem, settings, output, summary text,
/// resume, progress) -> summary text
using PyEngine = std::function<std::string(Problem*, const RunSettings&, const std::string&,
                                           const std::string&, bool, bool)>;
/// A dynamic analysis in Python: (problem, settings, output dir, summary,
/// source) -> summary
using PyAnalysis = std::function<std::string(Problem*, const RunSettings&, const std::string&,
                                             const std::string&, const std::string&)>;

ModelFactory factory(const PyModelFactory& f)
{
  return [f](const NamedMesh& mesh, const ModelSpec& spec) { return f(mesh, spec); };
}

/// The Python classes of the library's exceptions (set at import)
py::handle config_error, newton_failure, output_error, interrupted;

/// An engine written in Python raises the library's exceptions by their
/// Python classes; the driver gets them back as C++ exceptions
/// (Interrupted(signum, steps, t) from its arguments)
[[noreturn]] void rethrow(python_error& e)
{
  const std::string what = text(e.value());
  if (e.matches(config_error))
    throw ConfigError(what);
  if (e.matches(newton_failure))
    throw NewtonFailure(what);
  if (e.matches(output_error))
    throw OutputError(what);
  if (e.matches(interrupted))
  {
    const py::object value = e.value().attr("args");
    const auto args = py::cast<py::tuple>(value);
    throw Interrupted(py::cast<int>(args[0]), py::cast<int>(args[1]), py::cast<double>(args[2]));
  }
  throw;
}

Engine engine(const std::optional<PyEngine>& e)
{
  if (!e)
    return nullptr;
  return [e](Problem& problem, const RunSettings& settings, const std::filesystem::path& out,
             json summary, bool resume, bool progress)
  {
    try
    {
      return json::parse((*e)(&problem, settings, out.string(), summary.dump(), resume, progress));
    }
    catch (python_error& err)
    {
      rethrow(err);
    }
  };
}

Analysis analysis(const std::optional<PyAnalysis>& a)
{
  if (!a)
    return nullptr;
  return [a](Problem& problem, const RunSettings& settings, const std::filesystem::path& out,
             json summary, const std::string& source)
  {
    try
    {
      return json::parse((*a)(&problem, settings, out.string(), summary.dump(), source));
    }
    catch (python_error& err)
    {
      rethrow(err);
    }
  };
}

void declare_model(py::module_& m)
{
  class_<NamedMesh>(m, "NamedMesh",
                        "A mesh with its named boundaries (facet tags) and regions (cell tags)")
      .def_ro("mesh", &NamedMesh::mesh)
      .def_ro("facet_tags", &NamedMesh::facet_tags)
      .def_ro("cell_tags", &NamedMesh::cell_tags)
      .def_ro("tag_of", &NamedMesh::tag_of)
      .def_ro("region_of", &NamedMesh::region_of)
      .def("boundary_facets", &NamedMesh::boundary_facets, py::arg("name"))
      .def("region_cells", &NamedMesh::region_cells, py::arg("name"))
      .def("boundary_facets_of", &NamedMesh::boundary_facets_of, py::arg("boundary"),
           py::arg("region"));

  class_<MeshConversion>(m, "MeshConversion", "A mesh for a tool to make (mesh.h)")
      .def_ro("type", &MeshConversion::type)
      .def_prop_ro("input", [](const MeshConversion& j) { return j.input.string(); })
      .def_prop_ro("target", [](const MeshConversion& j) { return j.target.string(); })
      .def_prop_ro("log", [](const MeshConversion& j) { return j.log.string(); })
      .def_ro("size", &MeshConversion::size);

  class_<ModelSpec>(m, "ModelSpec", "Which pieces of the mesh carry which terms (model.h)")
      .def(py::init<>())
      .def_rw("manufactured", &ModelSpec::manufactured)
      .def_rw("contact", &ModelSpec::contact)
      .def_rw("obstacles", &ModelSpec::obstacles)
      .def_rw("with_obstacle", &ModelSpec::with_obstacle)
      .def_rw("electrodes", &ModelSpec::electrodes)
      .def_rw("boundary_keys", &ModelSpec::boundary_keys)
      .def_rw("degrees", &ModelSpec::degrees)
      .def_rw("axisymmetric", &ModelSpec::axisymmetric)
      .def_rw("linearised", &ModelSpec::linearised)
      .def_rw("expression_keys", &ModelSpec::expression_keys);

  class_<ConstantSource>(m, "ConstantSource",
                         "Where a Constant's value comes from (model.h)")
      .def(py::init<>())
      .def_rw("group", &ConstantSource::group)
      .def_rw("name", &ConstantSource::name)
      .def_rw("key", &ConstantSource::key)
      .def_rw("timed", &ConstantSource::timed)
      .def_rw("flag", &ConstantSource::flag)
      .def_rw("field", &ConstantSource::field);

  class_<RegionFields>(m, "RegionFields", "The cell-wise output of one region")
      .def(py::init<>())
      .def_rw("region", &RegionFields::region)
      .def_rw("cells", &RegionFields::cells)
      .def_rw("electric_displacement", &RegionFields::electric_displacement)
      .def_rw("stress", &RegionFields::stress);

  class_<ObstacleContact::Penetration>(m, "ObstaclePenetration",
                                       "The penetration on some facets (model.h)")
      .def(py::init<>())
      .def_rw("facets", &ObstacleContact::Penetration::facets)
      .def_rw("expression", &ObstacleContact::Penetration::expression);

  class_<ObstacleContact>(m, "ObstacleContact",
                          "The forms of a contact boundary with an obstacle (model.h)")
      .def(py::init<>())
      .def_rw("force", &ObstacleContact::force)
      .def_rw("pressure_load", &ObstacleContact::pressure_load)
      .def_rw("nodal_area", &ObstacleContact::nodal_area)
      .def_rw("contact_measure", &ObstacleContact::contact_measure)
      .def_rw("penetration", &ObstacleContact::penetration);

  class_<Model>(m, "Model", "The dolfinx objects of a run (model.h)")
      .def(py::init<>())
      .def_rw("mesh", &Model::mesh)
      .def_rw("axisymmetric", &Model::axisymmetric)
      .def_rw("W", &Model::W)
      .def_rw("P", &Model::P)
      .def_rw("x", &Model::x)
      .def_rw("x_prev", &Model::x_prev)
      .def_rw("x_dot", &Model::x_dot)
      .def_rw("K", &Model::K)
      .def_rw("C", &Model::C)
      .def_rw("M", &Model::M)
      .def_rw("constants", &Model::constants)
      .def_rw("materials", &Model::materials)
      .def_rw("loads", &Model::loads)
      .def_rw("data_fields", &Model::data_fields)
      .def_rw("load_data_fields", &Model::load_data_fields)
      .def_rw("sources", &Model::sources)
      .def_rw("contact_facets", &Model::contact_facets)
      .def_rw("F", &Model::F)
      .def_rw("J", &Model::J)
      .def_rw("J_contact", &Model::J_contact)
      .def_rw("contact_force", &Model::contact_force)
      .def_rw("spring_force", &Model::spring_force)
      .def_rw("obstacles", &Model::obstacles)
      .def_rw("fields", &Model::fields)
      .def_rw("u_exact", &Model::u_exact)
      .def_rw("phi_exact", &Model::phi_exact)
      .def_rw("squared_errors", &Model::squared_errors)
      .def_rw("boundary_measures", &Model::boundary_measures)
      .def_rw("electrode_charge", &Model::electrode_charge)
      .def_rw("contact_pressure_load", &Model::contact_pressure_load)
      .def_rw("contact_nodal_area", &Model::contact_nodal_area)
      .def_rw("L", &Model::L);
}

void declare_settings(py::module_& m)
{
  class_<NewtonSettings>(m, "NewtonSettings")
      .def_ro("rtol", &NewtonSettings::rtol)
      .def_ro("atol", &NewtonSettings::atol)
      .def_ro("max_iterations", &NewtonSettings::max_iterations)
      .def_ro("max_step_halvings", &NewtonSettings::max_step_halvings);
  class_<OutputSettings>(m, "OutputSettings")
      .def_ro("xdmf", &OutputSettings::xdmf)
      .def_ro("nodal", &OutputSettings::nodal);
  class_<AnalysisSettings>(m, "AnalysisSettings", "A dynamic analysis (settings.h)")
      .def_prop_ro("kind",
                   [](const AnalysisSettings& a) -> std::string
                   {
                     return a.kind == AnalysisSettings::Kind::modal      ? "modal"
                            : a.kind == AnalysisSettings::Kind::harmonic ? "harmonic"
                                                                         : "none";
                   })
      .def_ro("at_end", &AnalysisSettings::at_end)
      .def_ro("modes", &AnalysisSettings::modes)
      .def_ro("target", &AnalysisSettings::target)
      .def_ro("frequencies", &AnalysisSettings::frequencies);
  class_<RunSettings>(m, "RunSettings")
      .def_ro("T", &RunSettings::T)
      .def_ro("steps", &RunSettings::steps)
      .def_ro("newton", &RunSettings::newton)
      .def_ro("reuse_factorisation", &RunSettings::reuse_factorisation)
      .def_ro("symmetric", &RunSettings::symmetric)
      .def_prop_ro("linear", [](const RunSettings& s) -> std::string
                   { return s.linear == LinearSolver::iterative ? "iterative" : "direct"; })
      .def_ro("petsc_options", &RunSettings::petsc_options)
      .def_ro("probes", &RunSettings::probes)
      .def_ro("output", &RunSettings::output)
      .def_ro("analysis", &RunSettings::analysis);
}

void declare_problem(py::module_& m)
{
  class_<Problem>(m, "Problem", "A Model with its Dirichlet conditions (problem.h)")
      .def_prop_ro("bcs",
                             [](const Problem& p)
                             {
                               std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>>
                                   out(p.bcs().begin(), p.bcs().end());
                               return out;
                             })
      .def_prop_ro(
          "fixed_bcs",
          [](const Problem& p)
          {
            std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>> out;
            for (const auto& bc : p.bcs())
              if (std::none_of(p.electrodes.begin(), p.electrodes.end(),
                               [&bc](const Electrode& e) { return e.floating and e.bc == bc; }))
                out.push_back(bc);
            return out;
          },
          "The Dirichlet conditions but those of floating electrodes")
      .def_ro("electrodes", &Problem::electrodes)
      .def("target_charges", &Problem::target_charges)
      .def(
          "electrode_potentials",
          [](const Problem& p, const Array& x) { return p.electrode_potentials(view(x)); },
          py::arg("x"), "The mean potential of each electrode in x (owned entries)")
      .def(
          "reaction_charges",
          [](const Problem& p, const Array& r) { return p.reaction_charges(view(r)); },
          py::arg("r"), "Charge on each electrode: minus the sum of r (owned entries of an "
                        "unconstrained residual) over its dofs")
      .def("electrode_charges", &Problem::electrode_charges)
      .def_ro("u_dofs", &Problem::u_dofs)
      .def_ro("phi_dofs", &Problem::phi_dofs)
      .def_prop_ro("bc_dofs", &Problem::bc_dofs)
      .def_prop_ro("clamped_dofs", &Problem::clamped_dofs)
      .def("set_time", &Problem::set_time, py::arg("t"), py::arg("k"))
      .def("update_fields", &Problem::update_fields)
      .def("errors", &Problem::errors)
      .def(
          "force_balance",
          [](const Problem& p, const Array& r) { return p.force_balance(view(r)); },
          py::arg("r"), "The balance of forces in a residual (owned entries, before its BC rows)");
  class_<Electrode>(m, "Electrode", "A boundary with a prescribed or floating potential")
      .def_ro("name", &Electrode::name)
      .def_ro("dofs", &Electrode::dofs)
      .def_ro("floating", &Electrode::floating);
  class_<ForceBalance>(m, "ForceBalance", "What a residual says about equilibrium")
      .def_ro("unbalanced", &ForceBalance::unbalanced)
      .def_ro("supported", &ForceBalance::supported);
  m.def("contact_force", &contact_force, py::arg("problem"),
        "Resultant force of the foundation on the body at the current x");
  m.def("force_imbalance",
        py::overload_cast<const Problem&, const ForceBalance&>(&force_imbalance),
        py::arg("problem"), py::arg("balance"),
        "What Newton left on the free u dofs relative to the forces in play");
  m.attr("balance_tolerance") = balance_tolerance;
  class_<Acceptance>(m, "Acceptance", "The rule that accepts a step (acceptance.h)")
      .def(py::init<>())
      .def_rw("fields", &Acceptance::fields)
      .def_rw("charges", &Acceptance::charges)
      .def_rw("imbalance", &Acceptance::imbalance)
      .def("balanced", &Acceptance::balanced)
      .def("accepted", &Acceptance::accepted, py::arg("rtol"));
  m.def("imbalance_clause",
        py::overload_cast<const Acceptance&, const Problem&>(&imbalance_clause), py::arg("acceptance"), py::arg("problem"),
        "The failure message's clause on unbalanced forces ('' when they balance)");
}
/// Interrupted crosses to Python with (signum, steps, t), so that an engine
/// written in Python can let it through to the driver
template <typename F>
auto raising_interrupted(F&& f)
{
  try
  {
    return f();
  }
  catch (const Interrupted& e)
  {
    PyErr_SetObject(interrupted.ptr(), py::make_tuple(e.signum, e.steps, e.t).ptr());
    throw python_error();
  }
}

void declare_record(py::module_& m)
{
  class_<FieldNorms>(m, "FieldNorms", "Norms of one field's residual")
      .def(constructor([](double residual, double scaled, double relative, double update)
                    { return FieldNorms{residual, scaled, relative, update}; }),
           py::arg("residual"), py::arg("scaled_residual"), py::arg("relative"),
           py::arg("update"))
      .def_ro("residual", &FieldNorms::residual)
      .def_ro("scaled_residual", &FieldNorms::scaled_residual)
      .def_ro("relative", &FieldNorms::relative)
      .def_ro("update", &FieldNorms::update);
  class_<StepState>(m, "StepState", "The step control after an accepted step")
      .def(constructor(
               [](int step, int nominal, double t, double k, double k_last, double k_J)
               { return StepState{step, nominal, t, k, k_last, k_J}; }),
           py::arg("step"), py::arg("nominal"), py::arg("t"), py::arg("k"), py::arg("k_last"),
           py::arg("k_J"));
  class_<SolveReport>(m, "SolveReport", "How an accepted step was solved")
      .def(py::init<>())
      .def_rw("t", &SolveReport::t)
      .def_rw("k", &SolveReport::k)
      .def_rw("newton_iterations", &SolveReport::newton_iterations)
      .def_rw("factorisations", &SolveReport::factorisations)
      .def_rw("krylov_iterations", &SolveReport::krylov_iterations)
      .def_rw("history", &SolveReport::history)
      .def_rw("acceptance", &SolveReport::acceptance);
  class_<Probes>(m, "Probes", "Point evaluation of (u, phi) (diagnostics.h)")
      .def(constructor([](const Problem* p, const std::vector<std::array<double, 3>>& points,
                          const std::string& source) { return new Probes(*p, points, source); }),
           py::arg("problem"), py::arg("points"), py::arg("source"))
      .def("evaluate", &Probes::evaluate, py::arg("problem"),
           "(u..., phi) at each point, from the problem's collapsed u and phi")
      .def_ro("points", &Probes::points);
  class_<Record>(m, "Record", "The outputs and summary of a run (record.h)")
      .def(constructor(
               [](Problem* problem, const RunSettings& settings, const std::string& dir,
                  const std::string& summary, bool progress,
                  const std::optional<std::function<void(int, const std::string&)>>& observer)
               {
                 StepObserver on_step = nullptr;
                 if (observer)
                   on_step = [observer](int n, const json& step) { (*observer)(n, step.dump()); };
                 return new Record(*problem, settings, dir, json::parse(summary), false,
                                   progress, on_step);
               }),
           py::arg("problem"), py::arg("settings"), py::arg("dir"), py::arg("summary"),
           py::arg("progress"), py::arg("observer") = py::none(), keep_first_argument_alive())
      .def(
          "begin",
          [](Record& r, const StepState& s, const Array& x_n, const Array& x_prev,
             const Array& x_J) { r.begin(s, {view(x_n), view(x_prev), view(x_J)}); },
          "Write the step-0 checkpoint and the summary")
      .def(
          "accept",
          [](Record& r, const StepState& s, const SolveReport& report, const Array& x_n,
             const Array& x_prev, const Array& x_J, bool final, const std::string& timing)
          {
            return r.accept(s, report, {view(x_n), view(x_prev), view(x_J)}, final,
                            json::parse(timing))
                .dump();
          },
          "Record an accepted step (the Problem's x holds it); its record as JSON")
      .def("reject", &Record::reject)
      .def("fail", &Record::fail)
      .def("refuse", &Record::refuse)
      .def("interrupt",
           [](Record& r, int signum, const std::string& timing)
           { raising_interrupted([&] { r.interrupt(signum, json::parse(timing)); }); })
      .def_prop_ro("summary", [](const Record& r) { return r.summary().dump(); });
  m.def(
      "agreed_interrupt", [](MPICommWrapper comm) { return agreed_interrupt(comm.get()); },
      "The signal received on any rank, 0 if none (collective)");
}
} // namespace

PIEZO_MODULE(cpp, m)
{
  m.doc() = "libpiezocontact: the C++ core of piezocontact";
  config_error = register_exception<ConfigError>(m, "ConfigError", PyExc_ValueError);
  newton_failure = register_exception<NewtonFailure>(m, "NewtonFailure", PyExc_RuntimeError);
  output_error = register_exception<OutputError>(m, "OutputError", PyExc_OSError);
  interrupted = register_exception<Interrupted>(m, "Interrupted", PyExc_KeyboardInterrupt);
  m.attr("exit_config_error") = exit_config_error;
  m.attr("exit_run_error") = exit_run_error;
  m.attr("exit_output_error") = exit_output_error;

  declare_model(m);
  declare_settings(m);
  declare_problem(m);
  declare_record(m);

  m.def(
      "load_config",
      [](const std::string& path, const std::vector<std::string>& overrides)
      { return load_config(path, overrides).dump(); },
      py::arg("path"), py::arg("overrides"), "Read, override and validate a config file");
  m.def(
      "configure",
      [](const std::string& cfg, const std::vector<std::string>& overrides,
         const std::string& source)
      { return configure(json::parse(cfg), overrides, source).dump(); },
      py::arg("cfg"), py::arg("overrides"), py::arg("source"),
      "Override and validate a config given as JSON text");
  m.def(
      "build_mesh",
      [](const std::string& cfg, MPICommWrapper comm, std::optional<std::string> mesh_file,
         const std::string& source)
      {
        std::optional<std::filesystem::path> file;
        if (mesh_file)
          file = *mesh_file;
        return build_mesh(json::parse(cfg), comm.get(), file, source);
      },
      py::arg("cfg"), py::arg("comm"), nullable("mesh_file"), py::arg("source") = "config",
      "The mesh of a validated config: the built-in square, or an XDMF file with "
      "facet tags and its NAME.boundaries.json");
  m.def(
      "prepare_mesh",
      [](const std::string& cfg, const std::string& source, const std::string& out_dir,
         MPICommWrapper comm, const PyMeshConverter& convert) -> std::optional<std::string>
      {
        const auto file = prepare_mesh(json::parse(cfg), source, out_dir, comm.get(), convert);
        if (!file)
          return std::nullopt;
        return file->string();
      },
      py::arg("cfg"), py::arg("source"), py::arg("out_dir"), py::arg("comm"), py::arg("convert"),
      "The XDMF file of a config's mesh (None: built in); gmsh and msh meshes are made into "
      "OUT_DIR/mesh (mesh.h)");
  m.def(
      "name_mesh",
      [](std::shared_ptr<compat::Mesh> mesh, std::shared_ptr<const compat::MeshTags> facet_tags,
         std::shared_ptr<const compat::MeshTags> cell_tags,
         const std::map<std::string, int>& boundaries, const std::map<std::string, int>& regions,
         const std::string& source)
      { return name_mesh(mesh, facet_tags, cell_tags, boundaries, regions, source); },
      py::arg("mesh"), nullable("facet_tags"), nullable("cell_tags"), py::arg("boundaries"),
      py::arg("regions"), py::arg("source"),
      "A mesh given as dolfinx objects, its tags named {name: tag value} (mesh.h)");
  m.def(
      "checked_config",
      [](const std::string& cfg, const NamedMesh& mesh, MPICommWrapper comm,
         const std::string& source)
      { return checked_config(json::parse(cfg), mesh, comm.get(), source).dump(); },
      py::arg("cfg"), py::arg("mesh"), py::arg("comm"), py::arg("source"),
      "A validated config checked against its mesh, materials resolved (driver.h)");
  m.def(
      "model_spec", [](const std::string& cfg) { return model_spec(json::parse(cfg)); },
      py::arg("cfg"), "Which pieces of the mesh carry which terms, from a validated config");
  m.def(
      "set_constants", [](const std::string& cfg, const Model& model)
      { set_constants(json::parse(cfg), model); },
      py::arg("cfg"), py::arg("model"),
      "Fill the Constants of a model from a validated config (config.h)");
  m.def(
      "resumable_summary",
      [](const std::string& dir, const std::vector<std::string>& overrides,
         const std::string& solver)
      {
        const auto [summary, cfg] = resumable_summary(dir, overrides, solver);
        return std::pair(summary.dump(), cfg.dump());
      },
      py::arg("dir"), py::arg("overrides"), py::arg("solver"));
  m.def(
      "prepare_output",
      [](const std::string& dir, const std::string& source, MPICommWrapper comm)
      { prepare_output(dir, source, comm.get()); },
      py::arg("dir"), py::arg("source"), py::arg("comm"));
  m.def(
      "run_config",
      [](const std::string& cfg, const std::string& output, const std::string& source,
         const std::string& solver, bool progress, std::optional<std::string> resume,
         MPICommWrapper comm, const PyModelFactory& make_model,
         const PyMeshConverter& convert_mesh, const std::optional<PyEngine>& loop,
         const std::optional<std::function<void(int, const std::string&)>>& observer,
         const std::optional<PyAnalysis>& dynamics, const std::optional<NamedMesh>& mesh)
      {
        const json summary = resume ? json::parse(*resume) : json();
        RunRequest request{json::parse(cfg), output, source, solver, progress,
                           resume ? &summary : nullptr, convert_mesh, mesh ? &*mesh : nullptr};
        StepObserver on_step = nullptr;
        if (observer)
          on_step = [&observer](int n, const json& step) { (*observer)(n, step.dump()); };
        const InterruptScope interrupts;
        return run_config(request, comm.get(), factory(make_model), engine(loop), on_step,
                          analysis(dynamics))
            .dump();
      },
      py::arg("cfg"), py::arg("output"), py::arg("source"), py::arg("solver"),
      py::arg("progress"), nullable("resume"), py::arg("comm"), py::arg("make_model"),
      py::arg("convert_mesh"), py::arg("engine") = py::none(), py::arg("observer") = py::none(),
      py::arg("analysis") = py::none(), py::arg("mesh") = py::none(),
      "A run from a validated config (driver.h), on its mesh or the one given; output '': "
      "in memory; the summary as JSON text");
  m.def(
      "command_line",
      [](const std::string& program, const std::vector<std::string>& args, MPICommWrapper comm,
         const std::vector<std::tuple<std::string, std::string, PyModelFactory,
                                      std::optional<PyEngine>, std::optional<PyAnalysis>>>& choices,
         const PyMeshConverter& convert_mesh)
      {
        silence_hdf5_errors();
        std::vector<EngineChoice> engines;
        for (const auto& [name, solver, make_model, loop, dynamics] : choices)
          engines.push_back({name, solver, factory(make_model), engine(loop), analysis(dynamics)});
        return command_line(program, args, comm.get(), engines, convert_mesh);
      },
      py::arg("program"), py::arg("args"), py::arg("comm"), py::arg("engines"),
      py::arg("convert_mesh"),
      "The command line of piezo-contact with --engine choosing among "
      "(name, solver, model factory, time loop or None, dynamic analysis or None); returns "
      "the exit code");
}
