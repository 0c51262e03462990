// The dolfinx objects one run is made of, wherever their kernels come from:
// ffcx ahead of time (the executable) or dolfinx's JIT (the Python package).
// The library never builds a form itself; it drives the ones given here.
//
// The residual is a sum of terms, each a form integrated over one piece of
// the mesh with that piece's Constants: the bulk of each region with its
// material, the loads of each named boundary, the contact facets. Lists of
// forms are summed, so neither regions nor boundaries are limited in number.
#pragma once

#include "compat.h"

#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/MeshTags.h>
#include <array>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace piezocontact
{
/// A mesh with its named boundaries (facet tags) and regions (cell tags)
struct NamedMesh
{
  std::shared_ptr<compat::Mesh> mesh;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> facet_tags, cell_tags;
  std::map<std::string, int> tag_of;    ///< boundary name -> facet tag
  std::map<std::string, int> region_of; ///< region name -> cell tag

  /// Local indices of the facets of a boundary / the cells of a region
  std::vector<std::int32_t> boundary_facets(const std::string& name) const;
  std::vector<std::int32_t> region_cells(const std::string& name) const;
  /// The facets of a boundary that bound cells of a region
  std::vector<std::int32_t> boundary_facets_of(const std::string& boundary,
                                               const std::string& region) const;
};

using ConstantMap = std::map<std::string, std::shared_ptr<dolfinx::fem::Constant<double>>>;
using FunctionMap = std::map<std::string, std::shared_ptr<dolfinx::fem::Function<double>>>;
using FormList = std::vector<std::shared_ptr<const dolfinx::fem::Form<double>>>;

/// The cell-wise output of one region (its material enters the expressions)
struct RegionFields
{
  std::string region;
  std::vector<std::int32_t> cells;
  /// Electric displacement and Voigt stress at the cell midpoint
  std::shared_ptr<const dolfinx::fem::Expression<double>> electric_displacement, stress;
};

/// A contact boundary with an obstacle or a contact block of its own
/// (ModelSpec::obstacles): its forms, each with one term per region that
/// its facets bound (summed)
struct ObstacleContact
{
  /// force[i]: the terms of component i of the obstacle's resultant force
  /// on the body (N/m in 2D, N in 3D)
  std::vector<FormList> force;
  /// Linear forms on P: int lambda q ds and int q ds (the lumped pressure)
  FormList pressure_load, nodal_area;
  /// The measure of the facets where lambda > 0 (at quadrature points)
  FormList contact_measure;
  /// The penetration r at the nodes of u's space, on the cells of some of
  /// the boundary's facets (one per region)
  struct Penetration
  {
    std::vector<std::int32_t> facets;
    std::shared_ptr<const dolfinx::fem::Expression<double>> expression;
  };
  std::vector<Penetration> penetration;
};

/// Where the value of a Constant of the forms comes from (forms/piezo_forms.py
/// Datum): its group ("shared", "material" or "load"), its name, the config
/// key that sets it (from the top for shared data, within a region's
/// material or a boundary's entry otherwise; empty: the core sets it) and
/// whether that key may carry a history. A key the config leaves out
/// leaves the Constant zero.
struct ConstantSource
{
  std::string group, name, key;
  bool timed = false;
  /// A switch: 1 where the key's value is this string, else 0 (empty: the
  /// value is the key's number or numbers)
  std::string flag;
  /// A datum that may vary in space: the name of the forms' coefficient
  /// (Model::data_fields, load_data_fields) that carries it when the config gives it
  /// by expressions (empty: a Constant only)
  std::string field;
};

/// What the model builders need of a run's config: which pieces of the
/// mesh carry which terms (config.h model_spec)
struct ModelSpec
{
  /// A manufactured-solution run (the catalogue's variant)
  bool manufactured = false;
  /// The contact boundaries; the electrodes (a prescribed or floating
  /// potential), both among the mesh's named boundaries
  std::vector<std::string> contact, electrodes;
  /// The contact boundaries with an obstacle or a contact block of their
  /// own (config.h paper_foundation: the others are `contact`)
  std::vector<std::string> obstacles;
  /// Those of `obstacles` whose block gives an obstacle (the others are the
  /// paper's foundation with a block of their own)
  std::vector<std::string> with_obstacle;
  /// Each named boundary of the config -> the keys its entry sets (a term
  /// with a `where` key is instantiated on the boundaries that set it)
  std::map<std::string, std::vector<std::string>> boundary_keys;
  /// The Lagrange degrees of u and phi (config "elements")
  std::array<int, 2> degrees = {1, 1};
  /// The keys of the data the config gives by expressions (as the forms'
  /// data name them: "contact.gap", "traction", ...): a model whose
  /// spatial data are among them needs the kernels with their fields
  std::vector<std::string> expression_keys;
  /// The axisymmetric formulation of a 2D mesh (its own kernels: the hoop
  /// strain, the weight 2 pi r); plane strain and stress share the plane
  /// kernels and differ in their materials (materials.h)
  bool axisymmetric = false;
  /// A dynamic analysis follows (config "analysis"): the model carries the
  /// forms of a linearisation (Model::K, C, M)
  bool linearised = false;
};

/// A model builder has no kernels for the degrees a ModelSpec asks for (the
/// executable carries those compiled ahead of time); the driver turns it
/// into a ConfigError naming the key
struct DegreesNotCarried : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

struct Model
{
  NamedMesh mesh;
  /// The axisymmetric formulation (ModelSpec): u_r = 0 on the axis, four
  /// stress components
  bool axisymmetric = false;
  /// The mixed space of x = (u, phi): sub-space 0 is u, 1 is phi
  std::shared_ptr<const compat::FunctionSpace> W;
  /// The P1 space of the lumped contact pressure (null without contact forms)
  std::shared_ptr<const compat::FunctionSpace> P;
  /// The unknown at t_n and the state at t_{n-1}, coefficients of the forms
  std::shared_ptr<dolfinx::fem::Function<double>> x, x_prev;
  /// The velocity a linearisation holds (the forms K and C; null without)
  std::shared_ptr<dolfinx::fem::Function<double>> x_dot;
  /// The Constants shared by every term, by name (forms/piezo_forms.py
  /// shared_data); the library sets "k" (and "t" if present) each step
  ConstantMap constants;
  /// Per region: its material's Constants; per named boundary: its loads'
  std::map<std::string, ConstantMap> materials, loads;
  /// The fields of the shared data that may vary in space, and of each
  /// named boundary's, by datum name (ConstantSource::field): zero unless
  /// the config gives the datum by expressions (config.h spatial_loads)
  FunctionMap data_fields;
  std::map<std::string, FunctionMap> load_data_fields;
  /// Where each Constant's value comes from (config.h set_constants)
  std::vector<ConstantSource> sources;
  /// Local indices of the contact facets
  std::vector<std::int32_t> contact_facets;

  /// Residual terms (summed), Jacobian terms, and the terms of the Jacobian
  /// that depend on the state, every "J_state" term of the catalogue (J
  /// changes between iterates of one step only if they do)
  FormList F, J, J_contact;
  /// The applied loads, linear forms (F = internal forces - L): their size
  /// scales the force balance that accepts a step. Optional.
  FormList L;
  /// A linearisation about the state (x, x_dot) (ModelSpec::linearised;
  /// forms/terms.py linearised): the stiffness, each residual term's
  /// derivative with the velocity held (the Jacobian without the
  /// backward-Euler term), the damping (its derivative in the velocity:
  /// the viscosity) and the mass (rho, on u only), summed
  FormList K, C, M;
  /// Components of the foundation's resultant force on the body (N/m in
  /// 2D, N in 3D)
  FormList contact_force;
  /// Per boundary with a spring bed: the components of the bed's resultant
  /// force on the body
  std::map<std::string, FormList> spring_force;
  /// Per contact boundary with an obstacle or a block of its own
  std::map<std::string, ObstacleContact> obstacles;
  /// Cell-wise electric displacement and stress, per region
  std::vector<RegionFields> fields;

  /// Optional exact fields at the Constant "t", for Dirichlet data given as
  /// "exact" (manufactured solutions), and squared error functionals
  /// reported per step as their square roots
  std::shared_ptr<const dolfinx::fem::Expression<double>> u_exact, phi_exact;
  std::map<std::string, std::shared_ptr<const dolfinx::fem::Form<double>>> squared_errors;

  /// The functional 1 ds over each named boundary: its length (area in 3D)
  std::map<std::string, std::shared_ptr<const dolfinx::fem::Form<double>>> boundary_measures;

  /// Per electrode (a boundary with a prescribed or floating potential):
  /// its charge int D.nu ds, one term per region it bounds (summed)
  std::map<std::string, FormList> electrode_charge;

  /// Linear forms on P over the contact facets (one value per vertex):
  /// int p q ds and int q ds, whose ratio is the lumped contact pressure.
  /// Optional.
  std::shared_ptr<const dolfinx::fem::Form<double>> contact_pressure_load, contact_nodal_area;
};
} // namespace piezocontact
