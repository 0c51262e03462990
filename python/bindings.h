// bindings.h: the one place where wrappers.cpp meets its binding library.
// dolfinx's Python layer is pybind11 in 0.5 (Debian 12) and nanobind in 0.9
// (Debian 13), and ours must be the same library to exchange dolfinx
// objects with it. wrappers.cpp is written once, in nanobind's spelling
// (namespace `py`); for pybind11 this header supplies the few names that
// differ.
#pragma once

#include <dolfinx/common/version.h>

#include <cstddef>
#include <span>
#include <string>

#if DOLFINX_VERSION_MAJOR > 0 || DOLFINX_VERSION_MINOR >= 9
#define PIEZO_NANOBIND 1
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/filesystem.h>
#include <nanobind/stl/function.h>
#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>
#define PIEZO_MODULE(name, m) NB_MODULE(name, m)
#else
#define PIEZO_NANOBIND 0
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#define PIEZO_MODULE(name, m) PYBIND11_MODULE(name, m)
#endif

namespace piezocontact::bindings
{
#if PIEZO_NANOBIND
namespace py = nanobind;
using py::class_;
using py::python_error;

/// A float64 array as the C++ core reads it (contiguous, 1-D)
using Array = py::ndarray<const double, py::ndim<1>, py::c_contig>;

/// A constructor from a function returning a value or a new pointer
template <typename F>
auto constructor(F&& f)
{
  return py::new_(std::forward<F>(f));
}
/// Keep argument 1 (after `self`) of a factory constructor alive as long as
/// the object it makes (nanobind's __new__ counts the class as argument 1)
inline auto keep_first_argument_alive() { return py::keep_alive<0, 2>(); }

/// An argument that may be None (nanobind refuses None unless told)
inline py::arg nullable(const char* name) { return py::arg(name).none(); }

template <typename E>
py::handle register_exception(py::module_& m, const char* name, py::handle base)
{
  static py::exception<E> type(m, name, base);
  return type;
}

inline std::string text(py::handle h) { return py::str(h).c_str(); }
#else
namespace py = pybind11;
using python_error = pybind11::error_already_set;

/// pybind11's class_ with nanobind's names for attributes and properties
template <typename T, typename... Options>
class class_ : public pybind11::class_<T, Options...>
{
  using base = pybind11::class_<T, Options...>;

public:
  using base::base;
  template <typename... A>
  class_& def(A&&... a)
  {
    base::def(std::forward<A>(a)...);
    return *this;
  }
  template <typename... A>
  class_& def_ro(A&&... a)
  {
    base::def_readonly(std::forward<A>(a)...);
    return *this;
  }
  template <typename... A>
  class_& def_rw(A&&... a)
  {
    base::def_readwrite(std::forward<A>(a)...);
    return *this;
  }
  template <typename... A>
  class_& def_prop_ro(A&&... a)
  {
    base::def_property_readonly(std::forward<A>(a)...);
    return *this;
  }
};

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

template <typename F>
auto constructor(F&& f)
{
  return py::init(std::forward<F>(f));
}
inline auto keep_first_argument_alive() { return py::keep_alive<1, 2>(); }

inline py::arg nullable(const char* name) { return py::arg(name); }

template <typename E>
py::handle register_exception(py::module_& m, const char* name, py::handle base)
{
  return py::register_exception<E>(m, name, base);
}

inline std::string text(py::handle h) { return py::str(h); }
#endif

/// The values of a float64 array
inline std::span<const double> view(const Array& a) { return {a.data(), std::size_t(a.size())}; }
} // namespace piezocontact::bindings
