#include "petsc_options.h"

#include "compat.h"
#include "config.h"
#include "json_input.h"

#include <algorithm>
#include <cctype>
#include <petscksp.h>

namespace piezocontact
{
namespace
{
const std::string check_prefix = "piezocontact_check_";

/// A small two-field system set up as the C++ loop sets up its own: u (4
/// dofs in 2x2 blocks) and phi (2 dofs), split by name for a fieldsplit PC
class ToySystem
{
public:
  ToySystem()
  {
    MatCreateSeqAIJ(PETSC_COMM_SELF, size, size, 3, nullptr, &A);
    for (PetscInt i = 0; i < size; ++i)
    {
      MatSetValue(A, i, i, 4.0, INSERT_VALUES);
      if (i + 1 < size)
      {
        MatSetValue(A, i, i + 1, -1.0, INSERT_VALUES);
        MatSetValue(A, i + 1, i, -1.0, INSERT_VALUES);
      }
    }
    MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
    MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
    MatCreateVecs(A, &x, &b);
    VecSet(b, 1.0);
    const PetscInt u[] = {0, 1, 2, 3}, phi[] = {4, 5};
    ISCreateGeneral(PETSC_COMM_SELF, 4, u, PETSC_COPY_VALUES, &is_u);
    ISSetBlockSize(is_u, 2);
    ISCreateGeneral(PETSC_COMM_SELF, 2, phi, PETSC_COPY_VALUES, &is_phi);
  }
  ~ToySystem()
  {
    ISDestroy(&is_phi);
    ISDestroy(&is_u);
    VecDestroy(&b);
    VecDestroy(&x);
    MatDestroy(&A);
  }
  /// PETSc's error code when a KSP set up by `prefix` options solves it
  PetscErrorCode solve(const std::string& prefix) const
  {
    KSP ksp;
    PetscErrorCode code = KSPCreate(PETSC_COMM_SELF, &ksp);
    if (code)
      return code;
    KSPSetOptionsPrefix(ksp, prefix.c_str());
    KSPSetOperators(ksp, A, A);
    code = KSPSetFromOptions(ksp);
    PC pc;
    PetscBool split = PETSC_FALSE;
    if (!code and !(code = KSPGetPC(ksp, &pc)))
      PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCFIELDSPLIT, &split);
    if (!code and split)
    {
      code = PCFieldSplitSetIS(pc, "u", is_u);
      if (!code)
        code = PCFieldSplitSetIS(pc, "phi", is_phi);
    }
    if (!code)
      code = KSPSetUp(ksp);
    if (!code)
      code = KSPSolve(ksp, b, x);
    KSPDestroy(&ksp);
    return code;
  }

private:
  static constexpr PetscInt size = 6;
  Mat A;
  Vec x, b;
  IS is_u, is_phi;
};

/// PETSc's code when the loop's defaults and the first `n` options set up
/// and solve the toy system
PetscErrorCode try_options(const PetscOptionList& options, std::size_t n,
                           LinearSolver linear, const ToySystem& system)
{
  PetscOptionList first = loop_defaults(linear);
  first.insert(first.end(), options.begin(), options.begin() + n);
  const ScopedPetscOptions scoped(check_prefix, first);
  return system.solve(check_prefix);
}
} // namespace

ScopedPetscOptions::ScopedPetscOptions(const std::string& prefix,
                                       const PetscOptionList& options)
{
  for (const auto& [key, value] : options)
  {
    _names.push_back("-" + prefix + key);
    PetscOptionsSetValue(nullptr, _names.back().c_str(), value.c_str());
  }
}

ScopedPetscOptions::~ScopedPetscOptions()
{
  for (const auto& name : _names)
    PetscOptionsClearValue(nullptr, name.c_str());
}

QuietPetscErrors::QuietPetscErrors() { PetscPushErrorHandler(PetscReturnErrorHandler, nullptr); }

QuietPetscErrors::~QuietPetscErrors() { PetscPopErrorHandler(); }

std::string last_petsc_error(int code)
{
  const auto [text, specific] = compat::petsc_error_message(static_cast<PetscErrorCode>(code));
  std::string out = !specific.empty() ? specific : (!text.empty() ? text : "PETSc error");
  std::replace(out.begin(), out.end(), '\n', ' ');
  return printable(out, 200);
}

PetscOptionList loop_defaults(LinearSolver linear)
{
  if (linear == LinearSolver::iterative)
    // docs/solvers.md says why each: right preconditioning with the true
    // (Jacobi-scaled) residual as the norm; block Gauss-Seidel of u and phi;
    // smoothed aggregation with the rigid body modes on u (the code attaches
    // them), BoomerAMG with the 3D settings of hypre's manual on phi
    return {{"ksp_type", "gmres"},
            {"ksp_pc_side", "right"},
            {"ksp_norm_type", "unpreconditioned"},
            {"ksp_gmres_restart", "100"},
            {"ksp_max_it", "500"},
            {"ksp_rtol", "1e-12"},
            {"pc_type", "fieldsplit"},
            {"pc_fieldsplit_type", "multiplicative"},
            {"fieldsplit_u_ksp_type", "preonly"},
            {"fieldsplit_u_pc_type", "gamg"},
            {"fieldsplit_u_pc_gamg_threshold", "0.01"},
            {"fieldsplit_u_mg_levels_ksp_type", "chebyshev"},
            {"fieldsplit_u_mg_levels_pc_type", "jacobi"},
            {"fieldsplit_u_mg_levels_esteig_ksp_type", "cg"},
            {"fieldsplit_u_mg_levels_ksp_chebyshev_esteig_steps", "20"},
            {"fieldsplit_phi_ksp_type", "preonly"},
            {"fieldsplit_phi_pc_type", "hypre"},
            {"fieldsplit_phi_pc_hypre_type", "boomeramg"},
            {"fieldsplit_phi_pc_hypre_boomeramg_coarsen_type", "HMIS"},
            {"fieldsplit_phi_pc_hypre_boomeramg_interp_type", "ext+i"},
            {"fieldsplit_phi_pc_hypre_boomeramg_P_max", "4"}};
  PetscOptionList options = {{"ksp_type", "preonly"}, {"pc_type", "lu"}};
#if PETSC_HAVE_MUMPS
  options.emplace_back("pc_factor_mat_solver_type", "mumps");
#endif
  return options;
}

void check_petsc_options(const PetscOptionList& options, LinearSolver linear,
                         const std::string& source)
{
  const auto where = [&](const std::pair<std::string, std::string>& o)
  {
    return printable(source, 200) + ": solver.petsc_options." + printable(o.first, 60) + " = "
           + printable(o.second, 60);
  };
  for (const auto& o : options)
  {
    const auto& k = o.first;
    if (k.empty() or k[0] == '-'
        or !std::all_of(k.begin(), k.end(), [](unsigned char c)
                        { return std::isalnum(c) or c == '_'; }))
      throw ConfigError(where(o) + ": not a PETSc option name (letters, digits and _; "
                                   "no leading dash)");
  }
  const QuietPetscErrors quiet;
  const ToySystem system;
  if (!try_options(options, options.size(), linear, system))
    return;
  // The first option whose addition makes PETSc refuse: the culprit
  for (std::size_t n = 1; n <= options.size(); ++n)
    if (const PetscErrorCode code = try_options(options, n, linear, system))
      throw ConfigError(where(options[n - 1]) + ": refused by PETSc: " + last_petsc_error(code));
  throw ConfigError(printable(source, 200) + ": solver.petsc_options: refused by PETSc");
}
} // namespace piezocontact
