// The model of the executable: the kernels ffcx compiled ahead of time from
// the catalogue of terms (forms/terms.py), bound to a mesh.
#pragma once

#include <piezocontact/config.h>
#include <piezocontact/model.h>

namespace piezocontact::app
{
/// The forms on `mesh`, their pieces as `spec` says, their Constants zero
/// (the driver fills them)
Model compiled_model(const NamedMesh& mesh, const ModelSpec& spec);
} // namespace piezocontact::app
