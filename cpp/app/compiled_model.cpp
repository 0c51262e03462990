#include "compiled_model.h"
#include "piezo_forms_table.h" // generated from forms/terms.py: the kernels ffcx compiled

#include <dolfinx/fem/utils.h>
#include <algorithm>
#include <functional>
#include <numeric>

namespace piezocontact::app
{
using namespace dolfinx;

namespace
{
using compat::Coefficients;
using compat::Constants;
using forms::Piece;
using forms::Role;

ConstantMap zero_constants(const std::vector<forms::Datum>& data, const std::string& group)
{
  ConstantMap out;
  for (const auto& datum : data)
    if (datum.group == group)
    {
      const std::size_t size = std::accumulate(datum.shape.begin(), datum.shape.end(),
                                               std::size_t(1), std::multiplies{});
      const std::vector<double> zeros(size, 0.0);
      out[datum.name] = std::make_shared<fem::Constant<double>>(
          std::span<const double>(zeros), std::span<const std::size_t>(datum.shape));
    }
  return out;
}

/// The forms' coefficients of some fields (by their field names)
void add_fields(Coefficients& to, const FunctionMap& fields,
                const std::vector<forms::Datum>& data)
{
  for (const auto& datum : data)
    if (auto f = fields.find(datum.name); f != fields.end() and !datum.field.empty())
      to[datum.field] = f->second;
}

/// The union of Constant maps, as create_form takes them
Constants merged(std::initializer_list<const ConstantMap*> maps)
{
  Constants out;
  for (const auto* m : maps)
    out.insert(m->begin(), m->end());
  return out;
}

/// One instance of a term: the name of its piece ("" for the contact
/// facets, the exterior, the mesh), its entities (null: only its unmarked
/// integrals run) and its Constants
struct Instance
{
  std::string name;
  std::vector<std::int32_t> entities;
  bool marked;
  Constants constants;
  const FunctionMap* fields = nullptr; ///< a boundary's fields of its data
};

/// Builds a Model from the catalogue: one loop over its terms, each
/// instantiated on every piece of its kind
class Builder
{
public:
  Builder(const NamedMesh& named, const ModelSpec& spec) : _named(named), _spec(spec)
  {
    const int d = named.mesh->geometry().dim();
    check_carried(spec.degrees);
    // (a manufactured run has no expressions: config.cpp refuses them)
    _fields = !spec.manufactured
              and needs_fields(forms::data(d, spec.axisymmetric, false, true), spec);
    const auto data = forms::data(d, spec.axisymmetric, spec.manufactured, _fields);
    const auto [mixed, pressure] = forms::space_factories(d, spec.degrees);
    _m.mesh = named;
    _m.axisymmetric = spec.axisymmetric;
    _m.W = compat::mixed_space(named.mesh, mixed, spec.degrees);
    _m.P = compat::pressure_space(named.mesh, pressure);
    _m.x = std::make_shared<fem::Function<double>>(_m.W);
    _m.x->name = "x";
    _m.x_prev = std::make_shared<fem::Function<double>>(_m.W);
    _m.x_prev->name = "x_prev";
    _m.constants = zero_constants(data, "shared");
    for (const auto& [name, _] : named.region_of)
      _m.materials[name] = zero_constants(data, "material");
    const int k = forms::field_degree(spec.degrees);
    for (const auto& [name, _] : named.tag_of)
    {
      _m.loads[name] = zero_constants(data, "load");
      _m.load_data_fields[name] = zero_fields(data, "load", k);
    }
    _m.data_fields = zero_fields(data, "shared", k);
    for (const auto& datum : data)
      _m.sources.push_back(
          {datum.group, datum.name, datum.key, datum.timed, datum.flag, datum.field});
    for (const auto& name : spec.contact)
    {
      const auto facets = named.boundary_facets(name);
      _m.contact_facets.insert(_m.contact_facets.end(), facets.begin(), facets.end());
    }
    _coefficients = {{"x", _m.x}, {"x_prev", _m.x_prev}};
    if (spec.linearised)
    {
      _m.x_dot = std::make_shared<fem::Function<double>>(_m.W);
      _m.x_dot->name = "x_dot";
      _coefficients["x_dot"] = _m.x_dot;
    }
    _data = data;
    add_fields(_coefficients, _m.data_fields, data);
  }

  Model build()
  {
    const int d = _named.mesh->geometry().dim();
    for (const auto& term :
         forms::catalogue(d, _spec.axisymmetric, _spec.manufactured, _fields, _spec.degrees))
      for (const auto& piece : instances(term))
        place(term, piece);
    return std::move(_m);
  }

private:
  static void check_carried(forms::Degrees degrees)
  {
    const auto carried = forms::carried();
    if (std::find(carried.begin(), carried.end(), degrees) != carried.end())
      return;
    std::string list;
    for (const auto& [ku, kphi] : carried)
      list += (list.empty() ? "" : ", ") + std::to_string(ku) + "/" + std::to_string(kphi);
    throw DegreesNotCarried("the executable carries the degrees (u/phi) " + list
                            + "; `python3 -m piezocontact` compiles any degree");
  }

  /// A zero field for each datum of a group that may vary in space, on
  /// spaces shared by the data of one shape
  FunctionMap zero_fields(const std::vector<forms::Datum>& data, const std::string& group,
                          int degree)
  {
    FunctionMap out;
    for (const auto& datum : data)
      if (datum.group == group and !datum.field.empty())
      {
        auto& V = _field_spaces[datum.shape];
        if (!V)
          V = compat::field_space(_named.mesh, degree, datum.shape);
        out[datum.name] = std::make_shared<fem::Function<double>>(V);
      }
    return out;
  }

  /// Whether the config gives some datum that has a field by expressions
  static bool needs_fields(const std::vector<forms::Datum>& data, const ModelSpec& spec)
  {
    const auto& keys = spec.expression_keys;
    return std::any_of(data.begin(), data.end(), [&](const forms::Datum& datum)
                       { return !datum.field.empty()
                                and std::find(keys.begin(), keys.end(), datum.key) != keys.end(); });
  }

  bool sets(const std::string& boundary, const std::string& key) const
  {
    const auto keys = _spec.boundary_keys.find(boundary);
    return keys != _spec.boundary_keys.end()
           and std::find(keys->second.begin(), keys->second.end(), key) != keys->second.end();
  }

  /// The pieces a term is instantiated on, in a fixed order (the sums of
  /// the terms are then the same on every run)
  std::vector<Instance> instances(const forms::Term& term) const
  {
    const Constants shared = merged({&_m.constants});
    const ConstantMap* one_material
        = _m.materials.size() == 1 ? &_m.materials.begin()->second : &_m.constants;
    std::vector<Instance> out;
    switch (term.piece)
    {
    case Piece::region:
      for (const auto& [name, material] : _m.materials)
        out.push_back({name, _named.region_cells(name), true, merged({&_m.constants, &material})});
      break;
    case Piece::boundary:
      for (const auto& [name, load] : _m.loads)
        if (term.where.empty() or sets(name, term.where))
          out.push_back({name, _named.boundary_facets(name), true, merged({&_m.constants, &load}),
                         &_m.load_data_fields.at(name)});
      break;
    case Piece::contact:
      out.push_back({"", _m.contact_facets, true, shared});
      break;
    case Piece::electrode: // one term per region it bounds, on every rank
      for (const auto& name : _spec.electrodes)
        for (const auto& [region, material] : _m.materials)
          out.push_back({name, _named.boundary_facets_of(name, region), true,
                         merged({&_m.constants, &material})});
      break;
    case Piece::exterior: // a manufactured run has one material (checked)
      out.push_back({"", {}, false, merged({&_m.constants, one_material})});
      break;
    case Piece::mesh:
      out.push_back({"", {}, false, shared});
      break;
    case Piece::obstacle: // one term per region its facets bound, on every rank
      for (const auto& name : _spec.obstacles)
        for (const auto& [region, material] : _m.materials)
          out.push_back({name, _named.boundary_facets_of(name, region), true,
                         merged({&_m.constants, &_m.loads.at(name), &material}),
                         &_m.load_data_fields.at(name)});
      break;
    }
    return out;
  }

  void place(const forms::Term& term, const Instance& piece)
  {
    const bool linearisation
        = term.role == Role::K or term.role == Role::C or term.role == Role::M;
    if (linearisation and !_spec.linearised)
      return;
    const bool cells = term.piece == Piece::region or term.piece == Piece::mesh;
    if (term.expression)
      return place_expression(term, piece);
    const int rank = term.form->rank;
    std::vector<std::shared_ptr<const compat::FunctionSpace>> spaces(
        rank, term.space == forms::Space::P ? _m.P : _m.W);
    Coefficients coefficients = _coefficients;
    if (piece.fields)
      add_fields(coefficients, *piece.fields, _data);
    const auto form = compat::create_form(
        *term.form, spaces, coefficients, piece.constants,
        cells ? fem::IntegralType::cell : fem::IntegralType::exterior_facet,
        piece.marked ? &piece.entities : nullptr, _named.mesh);
    switch (term.role)
    {
    case Role::F:
      return _m.F.push_back(form);
    case Role::L:
      return _m.L.push_back(form);
    case Role::J_state:
      _m.J_contact.push_back(form);
      [[fallthrough]];
    case Role::J:
      return _m.J.push_back(form);
    case Role::K:
      return _m.K.push_back(form);
    case Role::C:
      return _m.C.push_back(form);
    case Role::M:
      return _m.M.push_back(form);
    case Role::output:
      return place_output(term, piece, form);
    }
  }

  void place_output(const forms::Term& term, const Instance& piece,
                    const std::shared_ptr<const fem::Form<double>>& form)
  {
    if (term.slot == "boundary_measures")
      _m.boundary_measures[piece.name] = form;
    else if (term.slot == "electrode_charge")
      _m.electrode_charge[piece.name].push_back(form);
    else if (term.slot == "contact_force")
      _m.contact_force.push_back(form);
    else if (term.slot == "spring_force")
      _m.spring_force[piece.name].push_back(form);
    else if (term.slot == "contact_pressure_load")
      _m.contact_pressure_load = form;
    else if (term.slot == "contact_nodal_area")
      _m.contact_nodal_area = form;
    else if (term.slot == "obstacle_force")
    {
      auto& force = _m.obstacles[piece.name].force;
      const std::size_t i = term.name.back() - 'x'; // obstacle_force_x, _y, _z
      force.resize(std::max(force.size(), i + 1));
      force[i].push_back(form);
    }
    else if (term.slot == "obstacle_pressure_load")
      _m.obstacles[piece.name].pressure_load.push_back(form);
    else if (term.slot == "obstacle_nodal_area")
      _m.obstacles[piece.name].nodal_area.push_back(form);
    else if (term.slot == "obstacle_contact_measure")
      _m.obstacles[piece.name].contact_measure.push_back(form);
    else if (term.slot == "squared_errors")
      _m.squared_errors[term.name] = form;
    else
      throw std::logic_error("forms/terms.py: no Model slot " + term.slot + " for " + term.name);
  }

  void place_expression(const forms::Term& term, const Instance& piece)
  {
    Coefficients coefficients = _coefficients;
    if (piece.fields)
      add_fields(coefficients, *piece.fields, _data);
    auto e = compat::create_expression(*term.expression, coefficients, piece.constants,
                                       _named.mesh);
    if (term.slot == "obstacle_penetration")
      _m.obstacles[piece.name].penetration.push_back({piece.entities, e});
    else if (term.slot == "u_exact")
      _m.u_exact = e;
    else if (term.slot == "phi_exact")
      _m.phi_exact = e;
    else if (term.slot == "electric_displacement" or term.slot == "stress")
    {
      auto fields = std::find_if(_m.fields.begin(), _m.fields.end(),
                                 [&](const RegionFields& f) { return f.region == piece.name; });
      if (fields == _m.fields.end())
        fields = _m.fields.insert(fields, {piece.name, piece.entities, nullptr, nullptr});
      (term.slot == "stress" ? fields->stress : fields->electric_displacement) = e;
    }
    else
      throw std::logic_error("forms/terms.py: no Model slot " + term.slot + " for " + term.name);
  }

  const NamedMesh& _named;
  const ModelSpec& _spec;
  Model _m;
  Coefficients _coefficients; ///< x, x_prev and the shared data's fields
  std::vector<forms::Datum> _data;
  bool _fields = false; ///< the kernels with the fields of spatial data
  std::map<std::vector<std::size_t>, std::shared_ptr<compat::FunctionSpace>> _field_spaces;
};
} // namespace

Model compiled_model(const NamedMesh& named, const ModelSpec& spec)
{
  return Builder(named, spec).build();
}
} // namespace piezocontact::app
