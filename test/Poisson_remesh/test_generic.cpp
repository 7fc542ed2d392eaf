// Every entry point on any FaceGraph (issue 23): a plain Polyhedron_3 (no ids in its items), a
// Surface_mesh over another kernel, a user vertex_point_map, and input and output of different
// types. The judges are CGAL's (AABB distance to the surface the map describes, validity,
// Euler characteristic), not the package's.
#include "analytic_meshes.h"
#include "test_support.h"

#include <Poisson_remesh/Boundary/Circular_available_boundary.h>
#include <Poisson_remesh/Features/detect_features.h>
#include <Poisson_remesh/Sampling/Boundary_sampler.h>
#include <Poisson_remesh/Geodesic/Exact_geodesic_oracle.h>
#include <Poisson_remesh/density_fields.h>
#include <Poisson_remesh/poisson_disk_sample.h>
#include <Poisson_remesh/poisson_remesh.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PR = Poisson_remesh;

namespace {

// the largest distance of a vertex of `out` to the surface of `in` read through `in_vpm`
template <class Out, class In, class InVPM>
double farthest_vertex(const Out& out, const In& in, InVPM in_vpm)
{
  typedef typename boost::property_traits<InVPM>::value_type P;
  typedef typename CGAL::Kernel_traits<P>::Kernel KK;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<KK, CGAL::AABB_face_graph_triangle_primitive<In, InVPM>>> Tree;
  Tree tree(faces(in).first, faces(in).second, in, in_vpm);
  double worst = 0;
  for(auto v : vertices(out)) {
    const auto p = get(CGAL::vertex_point, out, v);
    worst = std::max(worst, std::sqrt(CGAL::to_double(tree.squared_distance(P(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()))))));
  }
  return worst;
}

template <class M>
long euler_characteristic(const M& m)
{
  return long(vertices(m).size()) - long(edges(m).size()) + long(faces(m).size());
}

} // namespace

TEST_CASE("every entry point runs on a plain Polyhedron_3 (items without ids)", "[generic][polyhedron]")
{
  typedef CGAL::Polyhedron_3<K> Polyhedron;
  Polyhedron in, out;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elephant.off"), in);
  REQUIRE(faces(in).size() > 0);
  const PR::Feature_set<Polyhedron> features = PR::detect_features(in);
  CHECK(features.corners.size() < vertices(in).size());
  std::vector<PR::Poisson_sample<Polyhedron, K::Point_3>> samples;
  PR::poisson_disk_sample(in, std::back_inserter(samples), PR::parameters::target_vertex_count(400).random_seed(2u));
  CHECK(samples.size() > 300);
  PR::Exact_geodesic_oracle<Polyhedron> oracle(in);
  const auto f = *faces(in).first;
  oracle.propagate({f, {{1.0, 0.0, 0.0}}}, 0.05);
  const auto d = oracle.distance(source(halfedge(f, in), in));
  REQUIRE(d);
  CHECK(*d == Approx(0.0));
  const auto run = PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(600).random_seed(2u).regrading_attempts(1u));
  CHECK(CGAL::is_valid_polygon_mesh(out));
  CHECK(euler_characteristic(out) == euler_characteristic(in));
  CHECK(run.sampling.number_of_samples > 500);
  CHECK(farthest_vertex(out, in, get(CGAL::vertex_point, in)) < 1e-9);
  const PR::Quality_report q = PR::quality_report(out, in);
  CHECK(q.min_angle > 20);   // (a genericity test: the quality tests are elsewhere)
  CHECK(*q.hausdorff < 0.05);
  // the curvature density (measured beside the feature edges) on it: the radii of a Surface_mesh
  // read from the same file, vertex for vertex
  Mesh sm;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elephant.off"), sm);
  REQUIRE(num_vertices(sm) == num_vertices(in));
  const auto np = PR::parameters::target_vertex_count(400).density(PR::Curvature_density());
  const std::vector<double> radii = PR::disk_radii(in, np), expected = PR::disk_radii(sm, np);
  REQUIRE(radii.size() == expected.size());
  // (the same up to rounding: the meshes list their neighbours, edges and faces in other orders)
  for(std::size_t i = 0; i < radii.size(); ++i) CHECK(radii[i] == Approx(expected[i]).epsilon(1e-6));
}

TEST_CASE("a Polyhedron_3 remesh is the same in every run of a seed, wherever its elements lie in memory", "[generic][polyhedron][determinism]")
{
  // A Polyhedron_3's descriptors are addresses: a step that visited its elements sorted by them
  // made another remesh in each run (address-space randomization). Here the heap between the runs
  // is left full of holes of many sizes, so that each run's elements lie elsewhere, in another
  // order of addresses.
  typedef CGAL::Polyhedron_3<K> Polyhedron;
  Polyhedron in;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elephant.off"), in);
  std::vector<std::vector<K::Point_3>> outputs;
  std::vector<std::unique_ptr<char[]>> holes;
  for(int run = 0; run < 3; ++run) {
    Polyhedron out;
    PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(1500).random_seed(1u));
    outputs.emplace_back();
    for(auto v : vertices(out)) outputs.back().push_back(v->point());
    for(int i = 0; i < 20000; ++i) holes.emplace_back(new char[16 + (i * 7919) % 400]);
    for(std::size_t i = 0; i < holes.size(); i += 2) holes[i].reset();
  }
  REQUIRE(outputs[0].size() > 1000);
  CHECK(outputs[1] == outputs[0]);
  CHECK(outputs[2] == outputs[0]);
}

TEST_CASE("the remesher runs on a Surface_mesh over Simple_cartesian<double>", "[generic][kernel]")
{
  typedef CGAL::Simple_cartesian<double> SC;
  typedef CGAL::Surface_mesh<SC::Point_3> SC_mesh;
  SC_mesh in, out;
  PR::read_surface_mesh(test_support::data_mesh("meshes/fandisk.off"), in);
  const auto run = PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(1500).random_seed(1u));
  CHECK(CGAL::is_valid_polygon_mesh(out));
  CHECK(CGAL::is_closed(out));
  CHECK(euler_characteristic(out) == euler_characteristic(in));
  CHECK(run.sampling.number_of_corners > 10);
  CHECK(farthest_vertex(out, in, get(CGAL::vertex_point, in)) < 1e-9);
  const PR::Quality_report q = PR::quality_report(out, in);
  CHECK(q.min_angle > 15);   // (inexact predicates; a genericity test: the quality tests are elsewhere)
}

TEST_CASE("a user vertex_point_map is honoured: the output lies on the surface it describes", "[generic][vpm]")
{
  // the unit cube, read through a map that scales it by 3
  Mesh in = analytic::cube(4).to_mesh<Mesh>();
  auto scaled = in.add_property_map<Mesh::Vertex_index, K::Point_3>("v:scaled").first;
  for(auto v : vertices(in)) {
    const K::Point_3& p = in.point(v);
    put(scaled, v, K::Point_3(3 * p.x(), 3 * p.y(), 3 * p.z()));
  }
  Mesh out;
  const auto run = PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(300).random_seed(3u).vertex_point_map(scaled));
  CHECK(run.number_of_leftover_input_vertices == 0);
  CHECK(num_vertices(out) > 250);
  CHECK(num_vertices(out) < 400);
  // every output vertex on the x3 cube (and so none on the unit cube's interior faces)
  CHECK(farthest_vertex(out, in, scaled) < 1e-9);
  double largest = 0;
  for(auto v : vertices(out)) largest = std::max(largest, std::abs(CGAL::to_double(out.point(v).x())));
  CHECK(largest == Approx(3.0));
  // the sampler and the features read it too: the corners are the x3 cube's
  std::vector<PR::Poisson_sample<Mesh, K::Point_3>> samples;
  PR::poisson_disk_sample(in, std::back_inserter(samples), PR::parameters::target_vertex_count(200).vertex_point_map(scaled));
  for(const auto& s : samples) CHECK(std::abs(s.point.x() - 1.5) <= 1.5 + 1e-9);
  std::size_t far = 0;
  for(const auto& s : samples) if(std::abs(s.point.x()) > 1.01) ++far;
  CHECK(far > samples.size() / 4);
  // and the quality report: the diagonal of the x3 cube
  CHECK(PR::quality_report(in, PR::parameters::vertex_point_map(scaled)).bbox_diagonal == Approx(3 * std::sqrt(3.0)));
}

TEST_CASE("input and output may be of different types: Surface_mesh in, Polyhedron_3 out", "[generic][types]")
{
  typedef CGAL::Polyhedron_3<K> Polyhedron;
  Mesh in;
  PR::read_surface_mesh(test_support::data_mesh("meshes/triceratops.off"), in);
  Polyhedron out;
  const auto run = PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(1200).random_seed(5u).regrading_attempts(1u));
  CHECK(CGAL::is_valid_polygon_mesh(out));
  CHECK(CGAL::is_closed(out));
  CHECK(euler_characteristic(out) == euler_characteristic(in));
  CHECK(run.sampling.number_of_samples > 1000);
  CHECK(farthest_vertex(out, in, get(CGAL::vertex_point, in)) < 1e-9);
  const PR::Quality_report q = PR::quality_report(out, in);
  CHECK(q.mean_min_angle > 48);
}

// ------------------------------------------------------------------ the concepts' models, replaced
namespace {

// A user's GeodesicOracle: the exact one, counting its propagations (copies share the count).
template <class M>
struct Counting_oracle : PR::Exact_geodesic_oracle<M>
{
  typedef PR::Exact_geodesic_oracle<M> Base;
  using Base::Base;
  std::shared_ptr<std::size_t> propagations = std::make_shared<std::size_t>(0);
  template <class... A> void propagate(A&&... a) { ++*propagations; Base::propagate(std::forward<A>(a)...); }
};

// A user's BoundaryCurve: the circular one, counting its updates.
std::size_t boundary_updates = 0;
template <class M, class Arc>
struct Counting_boundary : PR::Circular_available_boundary<M, Arc>
{
  typedef PR::Circular_available_boundary<M, Arc> Base;
  using Base::Base;
  template <class... A> void update(A&&... a) { ++boundary_updates; Base::update(std::forward<A>(a)...); }
};

} // namespace

TEST_CASE("a user's geodesic oracle drives the sampler (named parameter geodesic_oracle)", "[generic][oracle]")
{
  Mesh m;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elephant.off"), m);
  typedef PR::Poisson_sample<Mesh, K::Point_3> Sample;
  std::vector<Sample> plain, counted;
  PR::poisson_disk_sample(m, std::back_inserter(plain), PR::parameters::target_vertex_count(600).random_seed(4u));
  Counting_oracle<Mesh> oracle(m);
  PR::poisson_disk_sample(m, std::back_inserter(counted), PR::parameters::target_vertex_count(600).random_seed(4u).geodesic_oracle(oracle));
  // it did the work (a propagation per sample at least) and, being the exact oracle, drew the same set:
  // the sampling tests judge that one (separation and coverage, Surface_mesh_shortest_path as judge)
  CHECK(*oracle.propagations >= counted.size());
  REQUIRE(counted.size() == plain.size());
  bool same = true;
  for(std::size_t i = 0; i < plain.size(); ++i) same = same && plain[i].point == counted[i].point;
  CHECK(same);
  // and the remesher takes it too
  Mesh out;
  const std::size_t before = *oracle.propagations;
  PR::poisson_remesh(m, out, PR::parameters::target_vertex_count(600).random_seed(4u).geodesic_oracle(oracle).regrading_attempts(0u));
  CHECK(*oracle.propagations > before + 500);
  CHECK(CGAL::is_valid_polygon_mesh(out));
  // but it cannot follow a copy of the input (here: made for a user point map)
  Mesh refused;
  CHECK_THROWS_AS(PR::poisson_remesh(m, refused, PR::parameters::geodesic_oracle(oracle).vertex_point_map(get(CGAL::vertex_point, m))),
                  std::invalid_argument);
}

TEST_CASE("a user's boundary curve drives the sampler (Boundary_sampler's fourth parameter)", "[generic][boundary]")
{
  Mesh m;
  PR::read_surface_mesh(test_support::data_mesh("meshes/fandisk.off"), m);
  typedef typename boost::property_map<Mesh, CGAL::vertex_point_t>::const_type VPM;
  typedef PR::Exact_geodesic_oracle<Mesh, VPM> Oracle;
  PR::Boundary_sampler<Mesh, VPM> plain(m, get(CGAL::vertex_point, m), 9);
  PR::Boundary_sampler<Mesh, VPM, Oracle, Counting_boundary<Mesh, typename Oracle::Iso_arc>> counted(m, get(CGAL::vertex_point, m), 9);
  for(auto* s : {&plain}) { s->set_radius(0.02); s->seed_components(); s->fill(); }
  boundary_updates = 0;
  counted.set_radius(0.02);
  counted.seed_components();
  counted.fill();
  CHECK(boundary_updates == counted.samples().size());
  REQUIRE(counted.samples().size() == plain.samples().size());
  bool same = true;
  for(std::size_t i = 0; i < plain.samples().size(); ++i) same = same && plain.samples()[i].point == counted.samples()[i].point;
  CHECK(same);
}

namespace {

// A user's Sampler: hands out a given sample set, counting its calls.
template <class Sample>
struct Given_samples
{
  const std::vector<Sample>* samples;
  std::size_t* calls;
  template <class M, class VPM, class Out>
  PR::Poisson_disk_sampling_result operator()(const M&, VPM, const PR::Feature_set<M>&, double radius,
                                              const std::vector<double>&, unsigned int, Out out) const
  {
    ++*calls;
    for(const Sample& s : *samples) *out++ = s;
    PR::Poisson_disk_sampling_result r;
    r.radius = radius;
    return r;
  }
};

// A user's Relaxer: leaves the mesh as it is and records the density it was given.
struct Density_recorder
{
  std::vector<double>* densities;
  template <class In, class InVPM, class M, class F, class X, class D, class N>
  PR::Relaxation_statistics relax(const In& input, InVPM, M& mesh, F is_feature, X is_fixed, D density, unsigned int, N) const
  {
    CHECK(num_faces(input) > 0);
    std::size_t features = 0, fixed = 0;
    for(auto e : edges(mesh)) if(get(is_feature, e)) ++features;
    for(auto v : vertices(mesh)) {
      if(get(is_fixed, v)) ++fixed;
      densities->push_back(get(density, v));
    }
    CHECK(fixed < num_vertices(mesh));
    (void)features;
    return {};
  }
};

} // namespace

TEST_CASE("a user's sampler drives poisson_remesh: the tessellation's vertices are its samples", "[generic][sampler]")
{
  Mesh in;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elephant.off"), in);
  typedef PR::Poisson_sample<Mesh, K::Point_3> Sample;
  // the user's vertices: a sampling the user made earlier (with the default sampler)
  std::vector<Sample> given;
  PR::poisson_disk_sample(in, std::back_inserter(given), PR::parameters::target_vertex_count(700).random_seed(8u));
  std::size_t calls = 0;
  std::vector<double> densities;
  Mesh out;
  // (no finer sampling around tips: a uniform density everywhere)
  const auto run = PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(700).feature_grading(false)
                                                 .sampler(Given_samples<Sample>{&given, &calls})
                                                 .relaxer(Density_recorder{&densities}));
  CHECK(calls == 1);   // (no remake with a user's sampler)
  CHECK(run.number_of_regrading_attempts == 0);
  CHECK(run.sampling.number_of_samples == given.size());
  // unrelaxed: every given point is an output vertex, and nothing else but leftover input vertices
  std::vector<K::Point_3> points, expected;
  for(auto v : vertices(out)) points.push_back(out.point(v));
  for(const Sample& s : given) expected.push_back(s.point);
  std::sort(points.begin(), points.end());
  std::sort(expected.begin(), expected.end());
  expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
  CHECK(points.size() == expected.size() + run.number_of_leftover_input_vertices);
  CHECK(std::includes(points.begin(), points.end(), expected.begin(), expected.end()));
  CHECK(CGAL::is_valid_polygon_mesh(out));
  CHECK(euler_characteristic(out) == euler_characteristic(in));
  // uniform density: 1 at every vertex
  REQUIRE(densities.size() == num_vertices(out));
  CHECK(*std::min_element(densities.begin(), densities.end()) == 1.0);
  CHECK(*std::max_element(densities.begin(), densities.end()) == 1.0);
}

TEST_CASE("a user's relaxer receives the adaptive density", "[generic][relaxer]")
{
  Mesh in, out;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elephant.off"), in);
  std::vector<double> densities;
  PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(900).random_seed(2u)
                                .density(PR::Curvature_density()).relaxer(Density_recorder{&densities}));
  REQUIRE(densities.size() == num_vertices(out));
  const double lo = *std::min_element(densities.begin(), densities.end()), hi = *std::max_element(densities.begin(), densities.end());
  CHECK(lo > 0);
  // the curvature density spans edge lengths up to 5 apart: densities up to 25 apart (Eq. 1)
  CHECK(hi > 4 * lo);
  CHECK(hi < 40 * lo);
}

TEST_CASE("the default models, passed explicitly, model the Sampler and Relaxer concepts", "[generic][sampler][relaxer]")
{
  Mesh in, a, b;
  PR::read_surface_mesh(test_support::data_mesh("meshes/fandisk.off"), in);
  const auto plain = PR::poisson_remesh(in, a, PR::parameters::target_vertex_count(1200).random_seed(6u).regrading_attempts(0u));
  PR::Lloyd_relaxer<Mesh, K> relaxer(in, PR::detect_features(in));
  const auto both = PR::poisson_remesh(in, b, PR::parameters::target_vertex_count(1200).random_seed(6u).regrading_attempts(0u)
                                                 .sampler(PR::Poisson_disk_sampler()).relaxer(relaxer));
  // the same sampling (the default sampler's), then the default relaxation
  CHECK(both.sampling.number_of_samples == plain.sampling.number_of_samples);
  CHECK(both.relaxation.moves > 0);
  CHECK(CGAL::is_valid_polygon_mesh(b));
  CHECK(euler_characteristic(b) == euler_characteristic(in));
  CHECK(farthest_vertex(b, in, get(CGAL::vertex_point, in)) < 1e-9);
  CHECK(PR::quality_report(b, in).min_angle > 20);
}
