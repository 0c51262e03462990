// The model of the executable: the kernels ffcx compiled ahead of time from
// forms/piezo_contact.ufl (and forms/manufactured.ufl for manufactured-
// solution runs), bound to a mesh.
#pragma once

#include <piezocontact/config.h>
#include <piezocontact/model.h>

namespace piezocontact::app
{
/// The forms on `mesh`, their Constants zero (the driver fills them)
Model compiled_model(const NamedMesh& mesh, const json& cfg);
} // namespace piezocontact::app
