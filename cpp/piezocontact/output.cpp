#include "output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <dolfinx/fem/utils.h>
#include <fstream>
#include <hdf5.h>
#include <pugixml.hpp>
#include <sstream>
#include <sys/statvfs.h>

namespace piezocontact
{
using namespace dolfinx;
namespace
{
namespace fs = std::filesystem;

int rank_of(MPI_Comm comm)
{
  int r;
  MPI_Comm_rank(comm, &r);
  return r;
}

std::string numbered(const char* format, int n)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, n);
  return buf;
}

/// Why writing into `dir` failed: a full disk is named as such (HDF5's own
/// message says only "can't write data"); otherwise errno, else `fallback`
std::string failure_reason(const fs::path& dir, int saved_errno, const std::string& fallback)
{
  struct statvfs s;
  if (saved_errno == ENOSPC
      or (::statvfs(dir.c_str(), &s) == 0 and s.f_bavail * s.f_frsize < (1u << 16)))
    return std::strerror(ENOSPC);
  if (saved_errno != 0)
    return std::strerror(saved_errno);
  return fallback;
}

/// Whether u or phi has nodes beyond the vertices (a degree above 1)
bool higher_degree(const Problem& problem)
{
  const std::size_t vertices = compat::topology(*problem.mesh).dim() + 1;
  return problem.V_u->dofmap()->cell_dofs(0).size() > vertices
         or problem.V_phi->dofmap()->cell_dofs(0).size() > vertices;
}

/// The fields written as nodal/NAME_NNNN.npy
constexpr const char* nodal_names[] = {"u", "phi", "contact_pressure"};

/// [x, y, (z,) values...] of the owned nodes of a collapsed Lagrange function, on rank 0
std::pair<std::vector<double>, std::size_t>
gather_nodal(const fem::Function<double>& f, MPI_Comm comm)
{
  const auto& V = *f.function_space();
  const int n = V.dofmap()->index_map->size_local();
  const int bs = V.dofmap()->index_map_bs();
  const int d = V.mesh()->geometry().dim();
  const std::size_t cols = d + bs;
  const auto coords = V.tabulate_dof_coordinates(false); // (num_dofs, 3)
  const auto values = compat::values(*f.x());
  std::vector<double> rows;
  rows.reserve(n * cols);
  for (int i = 0; i < n; ++i)
  {
    rows.insert(rows.end(), coords.begin() + 3 * i, coords.begin() + 3 * i + d);
    for (int c = 0; c < bs; ++c)
      rows.push_back(values[bs * i + c]);
  }
  int size;
  MPI_Comm_size(comm, &size);
  const int count = rows.size();
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  for (int r = 0; r < size; ++r)
    offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> all(rank_of(comm) == 0 ? offsets[size] : 0);
  MPI_Gatherv(rows.data(), count, MPI_DOUBLE, all.data(), counts.data(),
              offsets.data(), MPI_DOUBLE, 0, comm);
  return {all, cols};
}

/// Data paths of a dolfinx XDMF file are relative to it; the index sits one
/// directory up
void prefix_data_paths(pugi::xml_node node, const std::string& prefix)
{
  for (auto item : node.select_nodes(".//DataItem[@Format='HDF']"))
  {
    auto text = item.node().first_child();
    text.set_value((prefix + text.value()).c_str());
  }
}

/// Remove `path` if it exists, ignoring errors (clean-up on failure paths)
void remove_quietly(const fs::path& path)
{
  std::error_code ec;
  fs::remove(path, ec);
}

/// Files DIR/prefix*suffix whose number (the digits between) is > last,
/// but number `keep`
void remove_numbered_after(const fs::path& dir, const std::string& prefix,
                           const std::string& suffix, int last, int keep = -1)
{
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    return;
  for (const auto& entry : fs::directory_iterator(dir, ec))
  {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() + suffix.size() or name.rfind(prefix, 0) != 0
        or name.substr(name.size() - suffix.size()) != suffix)
      continue;
    const std::string digits
        = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    if (digits.find_first_not_of("0123456789") == std::string::npos
        and std::stoll(digits) > last and std::stoll(digits) != keep)
      remove_quietly(entry.path());
  }
}

const char* mesh_pointer
    = "xpointer(/Xdmf/Domain/Grid[@GridType='Uniform'][1]/*[self::Topology or "
      "self::Geometry])";
} // namespace

void write_file_atomic(const fs::path& path, const std::function<void(std::ostream&)>& write)
{
  const auto tmp = path.parent_path() / ("." + path.filename().string() + ".tmp");
  errno = 0;
  bool ok;
  {
    std::ofstream out(tmp, std::ios::binary);
    if (out)
      write(out);
    out.flush();
    ok = static_cast<bool>(out);
  }
  const int saved = errno;
  std::error_code ec;
  if (ok)
    fs::rename(tmp, path, ec);
  if (!ok or ec)
  {
    remove_quietly(tmp);
    throw OutputError("cannot write " + path.string() + ": "
                      + failure_reason(path.parent_path(), ok ? ec.value() : saved,
                                       "write failed"));
  }
}

void write_json_atomic(const fs::path& path, const json& value)
{
  write_file_atomic(path, [&](std::ostream& out) { out << value.dump(1) << "\n"; });
}

void write_npy(const fs::path& path, const std::vector<double>& data, std::size_t rows,
               std::size_t cols)
{
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': ("
                       + std::to_string(rows) + ", " + std::to_string(cols) + "), }";
  // magic(6) + version(2) + length(2) + header, padded to 64 bytes with '\n'
  header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
  header += '\n';
  write_file_atomic(path,
                    [&](std::ostream& out)
                    {
                      out.write("\x93NUMPY\x01\x00", 8);
                      const std::uint16_t len = header.size();
                      out.put(static_cast<char>(len & 0xff));
                      out.put(static_cast<char>(len >> 8));
                      out << header;
                      out.write(reinterpret_cast<const char*>(data.data()),
                                data.size() * sizeof(double));
                    });
}

std::tuple<std::vector<double>, std::size_t, std::size_t> read_npy(const fs::path& path)
{
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error(path.string() + ": "
                             + (errno ? std::strerror(errno) : "cannot be opened"));
  char magic[10];
  if (!in.read(magic, 10) or std::string(magic, 6) != "\x93NUMPY" or magic[6] != 1)
    throw std::runtime_error(path.string() + ": not a version-1 .npy file");
  const std::size_t len = static_cast<unsigned char>(magic[8])
                          | static_cast<unsigned char>(magic[9]) << 8;
  std::string header(len, '\0');
  in.read(header.data(), len);
  std::size_t rows = 0, cols = 0;
  if (header.find("'<f8'") == std::string::npos
      or header.find("'fortran_order': False") == std::string::npos
      or std::sscanf(header.c_str() + header.find("'shape': (") + 10, "%zu, %zu", &rows,
                     &cols)
             != 2)
    throw std::runtime_error(path.string() + ": not a C-ordered float64 matrix");
  std::vector<double> data(rows * cols);
  if (!in.read(reinterpret_cast<char*>(data.data()), data.size() * sizeof(double)))
    throw std::runtime_error(path.string() + ": truncated");
  return {std::move(data), rows, cols};
}

void collectively(MPI_Comm comm, bool on_this_rank, const std::function<void()>& action)
{
  std::string error;
  if (on_this_rank)
  {
    try
    {
      action();
    }
    catch (const std::exception& e)
    {
      error = e.what();
    }
  }
  int size;
  MPI_Comm_size(comm, &size);
  int first = error.empty() ? size : rank_of(comm);
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size)
    return;
  int len = error.size();
  MPI_Bcast(&len, 1, MPI_INT, first, comm);
  error.resize(len);
  MPI_Bcast(error.data(), len, MPI_CHAR, first, comm);
  throw OutputError(error);
}

void silence_hdf5_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

Writer::Writer(const Problem& problem, const OutputSettings& settings, const fs::path& dir,
               std::optional<int> resumed_step)
    : _problem(problem), _dir(dir), _nodal(settings.nodal), _xdmf(settings.xdmf)
{
  const bool root = rank_of(problem.comm) == 0;
  const int resume_step = resumed_step.value_or(0);
  collectively(problem.comm, root,
               [&]
               {
                 if (resume_step == 0)
                 {
                   // nothing of an earlier run in DIR may pass for this one's
                   fs::remove_all(dir / "solution");
                   fs::remove(dir / "solution.xdmf");
                   fs::remove(dir / "solution.h5");
                   for (const char* f : nodal_names)
                     remove_numbered_after(dir / "nodal", std::string(f) + "_", ".npy", -1);
                 }
                 remove_numbered_after(dir / "solution", "step_", ".h5", resume_step);
                 remove_numbered_after(dir / "solution", "step_", ".xdmf", -1);
                 // every checkpoint but the one resumed (a kill
                 // may land between a summary and the removal of its predecessor's)
                 remove_numbered_after(dir / "checkpoint", "state_", ".npy", -1,
                                       resumed_step.value_or(-1));
                 for (const char* f : nodal_names)
                   remove_numbered_after(dir / "nodal", std::string(f) + "_", ".npy",
                                         resume_step);
                 fs::create_directories(dir / "nodal");
                 fs::create_directories(dir / "solution");
               });
  if (!_xdmf)
    return;
  auto mesh = problem.mesh;
  const int d = mesh->geometry().dim();
  _D = std::make_shared<fem::Function<double>>(compat::dg0_space(mesh, d));
  _D->name = "D";
  // XDMF has no Voigt vector: one scalar field per component, named in the
  // 3D frame (axisymmetry: x = r, y the axis, z the hoop direction)
  const std::vector<std::string> voigt
      = problem.model.axisymmetric ? std::vector<std::string>{"xx", "yy", "zz", "xy"}
        : d == 2                   ? std::vector<std::string>{"xx", "yy", "xy"}
                                   : std::vector<std::string>{"xx", "yy", "zz", "yz", "xz", "xy"};
  _stress = std::make_shared<fem::Function<double>>(compat::dg0_space(mesh, voigt.size()));
  for (std::size_t c = 0; c < voigt.size(); ++c)
  {
    auto [Vc, map] = compat::collapse(*compat::sub(*_stress->function_space(), int(c)));
    _stress_components.push_back(std::make_shared<fem::Function<double>>(
        std::make_shared<compat::FunctionSpace>(std::move(Vc))));
    _stress_components.back()->name = "stress_" + voigt[c];
    _stress_maps.push_back(std::move(map));
  }
  _out = std::make_unique<OutputMesh>(mesh, higher_degree(problem));
  if (root)
    _index = std::make_unique<pugi::xml_document>();
  if (resume_step > 0)
  {
    collectively(problem.comm, root, [&] { load_index(resume_step); });
    return;
  }
  // The mesh goes in through dolfinx once, as solution.xdmf/.h5 (so that
  // XDMFFile::read_mesh still reads it there); that XML becomes the index
  const auto index = dir / "solution.xdmf";
  write_hdf5(index, [&](io::XDMFFile& f) { f.write_mesh(*_out->mesh()); });
  collectively(problem.comm, root,
               [&]
               {
                 if (!_index->load_file(index.c_str()))
                   throw OutputError("cannot write " + index.string() + ": "
                                     + failure_reason(dir, 0, "unreadable after writing"));
               });
}

Writer::~Writer() = default;

void Writer::write_hdf5(const fs::path& xdmf,
                        const std::function<void(io::XDMFFile&)>& write) const
{
  const auto h5 = fs::path(xdmf).replace_extension(".h5");
  std::string error;
  int saved_errno = 0;
  // XDMFFile::close() throws on a failed H5Fclose and leaves the handle set,
  // so its destructor would throw again (std::terminate): on failure the
  // object is deliberately leaked, the run ends anyway.
  std::unique_ptr<io::XDMFFile> file;
  try
  {
    errno = 0;
    file = std::make_unique<io::XDMFFile>(_problem.comm, xdmf, "w"); // H5Fcreate may fail
    write(*file);
    file->close();
  }
  catch (const std::exception& e)
  {
    saved_errno = errno;
    error = e.what();
    file.release();
  }
  int failed = !error.empty();
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_LOR, _problem.comm);
  if (!failed)
    return;
  const std::string reason = failure_reason(h5.parent_path(), saved_errno,
                                            error.empty() ? "HDF5 write failed" : error);
  if (rank_of(_problem.comm) == 0)
  {
    // The partial file's space may let the summary say what went wrong. It
    // is still open (leaked above): removing it alone would free nothing.
    std::error_code ec;
    fs::resize_file(h5, 0, ec);
    remove_quietly(h5);
    remove_quietly(xdmf);
  }
  throw OutputError("cannot write " + h5.string() + ": " + reason);
}

void Writer::load_index(int last_step)
{
  const auto path = _dir / "solution.xdmf";
  if (!_index->load_file(path.c_str()))
    throw OutputError("cannot resume: " + path.string() + " is missing or unreadable");
  // Steps written after the checkpoint are dropped: the resumed run rewrites them
  for (auto series : _index->select_nodes("/Xdmf/Domain/Grid[@GridType='Collection']"))
  {
    int count = 0;
    for (auto grid = series.node().child("Grid"); grid;)
    {
      auto next = grid.next_sibling("Grid");
      if (++count > last_step)
        series.node().remove_child(grid);
      grid = next;
    }
  }
  publish_index();
}

void Writer::write_xdmf_step(int step, double t)
{
  for (const auto& region : _problem.model.fields) // each with its material
  {
    _D->interpolate(*region.electric_displacement, region.cells);
    _stress->interpolate(*region.stress, region.cells);
  }
  const auto all = compat::values(*_stress->x());
  for (std::size_t c = 0; c < _stress_components.size(); ++c)
  {
    auto values = compat::mutable_values(*_stress_components[c]->x());
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] = all[_stress_maps[c][i]];
  }
  const std::string name = numbered("step_%06d", step);
  const auto step_xdmf = _dir / "solution" / (name + ".xdmf");
  // A new HDF5 file per step, never reopened: an append cut short by a kill
  // could damage a shared file's metadata, and every earlier step with it
  write_hdf5(step_xdmf,
             [&](io::XDMFFile& f)
             {
               for (const auto& fn : {_problem.u, _problem.phi, _D})
                 f.write_function((*_out)(*fn), t, "/Xdmf/Domain");
               if (_problem.contact_pressure)
                 f.write_function((*_out)(*_problem.contact_pressure), t, "/Xdmf/Domain");
               for (const auto& fn : _stress_components)
                 f.write_function((*_out)(*fn), t, "/Xdmf/Domain");
             });
  collectively(_problem.comm, rank_of(_problem.comm) == 0,
               [&]
               {
                 pugi::xml_document doc;
                 if (!doc.load_file(step_xdmf.c_str()))
                   throw OutputError("cannot write " + step_xdmf.string() + ": "
                                     + failure_reason(step_xdmf.parent_path(), 0,
                                                      "unreadable after writing"));
                 pugi::xml_node domain = _index->child("Xdmf").child("Domain");
                 for (auto src : doc.select_nodes("/Xdmf/Domain/Grid[@GridType='Collection']"))
                 {
                   const char* fname = src.node().attribute("Name").value();
                   pugi::xml_node series = domain.find_child_by_attribute("Grid", "Name", fname);
                   if (!series)
                   {
                     series = domain.append_child("Grid");
                     series.append_attribute("Name") = fname;
                     series.append_attribute("GridType") = "Collection";
                     series.append_attribute("CollectionType") = "Temporal";
                   }
                   for (auto grid : src.node().children("Grid"))
                   {
                     auto copy = series.append_copy(grid);
                     copy.child("xi:include").attribute("xpointer") = mesh_pointer;
                     prefix_data_paths(copy, "solution/");
                   }
                 }
                 fs::remove(step_xdmf);
                 publish_index();
               });
}

void Writer::publish_index() const
{
  write_file_atomic(_dir / "solution.xdmf",
                    [&](std::ostream& out) { _index->save(out, "  "); });
}

void Writer::write_step(int step, double t, bool final)
{
  if (_xdmf)
    write_xdmf_step(step, t);
  if (_nodal == "all" or (_nodal == "final" and final))
  {
    const std::string num = numbered("%04d", step);
    for (const auto& [name, f] : {std::pair{"u", _problem.u}, std::pair{"phi", _problem.phi},
                                  std::pair{"contact_pressure", _problem.contact_pressure}})
    {
      if (!f)
        continue;
      const auto [rows, cols] = gather_nodal(*f, _problem.comm);
      collectively(_problem.comm, rank_of(_problem.comm) == 0,
                   [&, &rows = rows, cols = cols, name = name]
                   {
                     write_npy(_dir / "nodal" / (std::string(name) + "_" + num + ".npy"),
                               rows, rows.size() / cols, cols);
                   });
    }
  }
}
} // namespace piezocontact
