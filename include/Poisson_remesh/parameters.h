// Poisson_remesh/parameters.h
//
// The package's named parameters, in one place.
//
// CGAL 5.5's CGAL::Named_function_parameters generates its member functions from CGAL's own
// list, so a package outside CGAL cannot add `.target_vertex_count(n)` to it. This header
// defines Poisson_remesh::Named_function_parameters, which *is a* CGAL::Named_function_parameters
// (so CGAL's get_parameter / choose_parameter and every CGAL function accept it) and has member
// functions for both lists: CGAL's (vertex_point_map, geom_traits, random_seed,
// number_of_iterations, edge_is_constrained_map, face_index_map, ...) and the package's own
// (internal/parameters_interface.h). One expression chains both:
//
//   namespace PR = Poisson_remesh::parameters;
//   PR::target_vertex_count(5000).random_seed(7).vertex_point_map(vpm).sharp_angle(60.)
//
// Start the chain from Poisson_remesh::parameters (it also has all of CGAL's free functions);
// a plain CGAL::parameters chain is accepted everywhere too, it just cannot name our parameters.
//
// Caveat: a few CGAL functions have an overload whose second argument is a face range (for
// example Polygon_mesh_processing::area(faces, tm, np) beside area(tm, np)); for those, overload
// resolution prefers the face-range overload for a type *derived* from CGAL's, so pass them a
// plain CGAL::parameters chain. The package's own functions accept both.

#ifndef POISSON_REMESH_PARAMETERS_H
#define POISSON_REMESH_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

namespace Poisson_remesh {

namespace internal_np {
#define POISSON_REMESH_add_named_parameter(X, Y, Z) enum X { Y };
#include <Poisson_remesh/internal/parameters_interface.h>
#undef POISSON_REMESH_add_named_parameter
} // namespace internal_np

/// A chain of named parameters that holds both CGAL's and the package's own: it *is a*
/// `CGAL::Named_function_parameters` (CGAL's functions accept it) with a member function for every
/// named parameter of both lists (`.target_vertex_count(n)`, `.vertex_point_map(vpm)`, ...). Start
/// a chain with a free function of `Poisson_remesh::parameters`; the user manual lists the
/// package's parameters.
template <typename T, typename Tag, typename Base = CGAL::internal_np::No_property>
struct Named_function_parameters
  : CGAL::Named_function_parameters<T, Tag, Base>
{
  /// the CGAL chain this one is
  typedef CGAL::Named_function_parameters<T, Tag, Base> cgal_type;
  /// this type
  typedef Named_function_parameters<T, Tag, Base> self;

  /// an empty chain
  Named_function_parameters() : cgal_type() {}
  /// a chain of one parameter, of value `v`
  Named_function_parameters(const T& v) : cgal_type(v) {}
  /// the parameter of value `v` in front of the chain `b`
  Named_function_parameters(const T& v, const Base& b) : cgal_type(v, b) {}

#define POISSON_REMESH_chain_parameter(TAG, Z)                                 \
  template <typename K>                                                        \
  Named_function_parameters<K, TAG, self> Z(const K& k) const                  \
  {                                                                            \
    return Named_function_parameters<K, TAG, self>(k, *this);                  \
  }
#define CGAL_add_named_parameter(X, Y, Z) POISSON_REMESH_chain_parameter(CGAL::internal_np::X, Z)
#include <CGAL/STL_Extension/internal/parameters_interface.h>
#undef CGAL_add_named_parameter
#define POISSON_REMESH_add_named_parameter(X, Y, Z) POISSON_REMESH_chain_parameter(Poisson_remesh::internal_np::X, Z)
#include <Poisson_remesh/internal/parameters_interface.h>
#undef POISSON_REMESH_add_named_parameter
#undef POISSON_REMESH_chain_parameter
};

namespace parameters {

using CGAL::parameters::choose_parameter;
using CGAL::parameters::get_parameter;
using CGAL::parameters::is_default_parameter;

/// the type of an empty chain: every parameter takes its default
typedef CGAL::parameters::Default_named_parameters Default_named_parameters;
/// an empty chain: every parameter takes its default
inline Default_named_parameters default_values() { return Default_named_parameters(); }

#define POISSON_REMESH_free_parameter(TAG, Z)                                  \
  template <typename K>                                                        \
  Named_function_parameters<K, TAG> Z(const K& k)                              \
  {                                                                            \
    return Named_function_parameters<K, TAG>(k);                               \
  }
#define CGAL_add_named_parameter(X, Y, Z) POISSON_REMESH_free_parameter(CGAL::internal_np::X, Z)
#include <CGAL/STL_Extension/internal/parameters_interface.h>
#undef CGAL_add_named_parameter
#define POISSON_REMESH_add_named_parameter(X, Y, Z) POISSON_REMESH_free_parameter(Poisson_remesh::internal_np::X, Z)
#include <Poisson_remesh/internal/parameters_interface.h>
#undef POISSON_REMESH_add_named_parameter
#undef POISSON_REMESH_free_parameter

} // namespace parameters
} // namespace Poisson_remesh

#endif // POISSON_REMESH_PARAMETERS_H
