// The mesh the XDMF files show the fields on. At degree 1, the problem's
// mesh. At a higher degree dolfinx 0.5's XDMF writer would keep only the
// vertex values of a field (a P2 field shown as its P1 interpolant): the
// fields are written on the mesh refined once instead, a Lagrange field by
// its values at the refined mesh's vertices (at degree 2 these are its
// nodes: the file holds every dof), a cell-wise field by its value in the
// parent cell.
#pragma once

#include "compat.h"

#include <map>
#include <memory>
#include <vector>

namespace piezocontact
{
class OutputMesh
{
public:
  /// `refine`: write on the mesh refined once (collective)
  OutputMesh(std::shared_ptr<compat::Mesh> mesh, bool refine);

  /// The mesh of the files
  std::shared_ptr<compat::Mesh> mesh() const { return _refined ? _refined : _mesh; }

  /// What to write for f (a P_k or DG0 field of the problem's mesh): f, or
  /// its values on the refined mesh at f's current state
  const dolfinx::fem::Function<double>& operator()(const dolfinx::fem::Function<double>& f);

private:
  /// Where the refined field takes its values: points of the problem's mesh
  /// and the local cells that hold them
  struct Transfer
  {
    std::shared_ptr<dolfinx::fem::Function<double>> target;
    std::vector<double> points;
    std::vector<std::int32_t> cells;
  };
  Transfer transfer_for(const dolfinx::fem::Function<double>& f) const;

  std::shared_ptr<compat::Mesh> _mesh, _refined;
  std::map<const dolfinx::fem::Function<double>*, Transfer> _transfers;
};
} // namespace piezocontact
