// Tests of the whole remesher (paper §3-§6): poisson_remesh() and the Lloyd relaxer.
#include "analytic_meshes.h"
#include "test_support.h"

#include <Poisson_remesh/poisson_remesh.h>
#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/read_surface_mesh.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Polyhedron_items_with_id_3.h>
#include <CGAL/Surface_mesh.h>

#include <catch2/catch.hpp>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif

#include <algorithm>
#include <iostream>
#include <memory>
#include <sstream>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
namespace PR = Poisson_remesh;

namespace {

// largest distance of an output vertex to the input surface, over the input's bbox diagonal
double vertices_off_input(const Mesh& out, const Mesh& in)
{
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_face_graph_triangle_primitive<Mesh>>> Tree;
  Tree tree(faces(in).first, faces(in).second, in);
  double worst = 0;
  for(auto v : vertices(out)) worst = std::max(worst, std::sqrt(CGAL::to_double(tree.squared_distance(out.point(v)))));
  return worst / PR::quality_report(in, PR::parameters::check_self_intersections(false)).bbox_diagonal;
}

// the smallest angle of m's triangles in degrees, computed here (not by the package's report)
double smallest_angle_degrees(const Mesh& m)
{
  double smallest = 180;
  for(auto f : faces(m)) {
    const auto h = halfedge(f, m);
    const Point p[3] = {m.point(source(h, m)), m.point(target(h, m)), m.point(target(next(h, m), m))};
    for(int i = 0; i < 3; ++i) {
      const K::Vector_3 u = p[(i + 1) % 3] - p[i], v = p[(i + 2) % 3] - p[i];
      smallest = std::min(smallest, std::acos(CGAL::to_double(u * v) / std::sqrt(CGAL::to_double(u.squared_length() * v.squared_length()))) * 180 / CGAL_PI);
    }
  }
  return smallest;
}

double longest_edge(const Mesh& m)
{
  double longest = 0;
  for(auto e : edges(m))
    longest = std::max(longest, std::sqrt(CGAL::to_double(CGAL::squared_distance(m.point(source(e, m)), m.point(target(e, m))))));
  return longest;
}

} // namespace

TEST_CASE("remeshed meshes keep the input's topology and lie on it", "[remesh]")
{
  for(const std::string name : {"meshes/fandisk.off", "meshes/elephant.off", "meshes/knot1.off", "meshes/bull.off",
                                "meshes/triceratops.off", "meshes/dino.off"}) {
    INFO(name);
    Mesh in, out;
    PR::read_surface_mesh(test_support::data_mesh(name), in);
    const auto run = PR::poisson_remesh(in, out, PR::parameters::random_seed(3u));
    const PR::Quality_report a = PR::quality_report(in), b = PR::quality_report(out, in);
    std::cout << "[poisson_remesh] " << name << ": V " << b.number_of_vertices << " (input " << a.number_of_vertices
              << "), min angle " << b.min_angle << ", mean min angle " << b.mean_min_angle << ", irregular "
              << b.irregular_share << ", Hausdorff " << *b.hausdorff << ", self-intersecting pairs "
              << b.number_of_self_intersecting_face_pairs << ", " << run.seconds() << " s\n";
    CHECK(CGAL::is_valid_polygon_mesh(out));
    CHECK(CGAL::is_closed(out));
    // no removed elements are left behind (the relaxer's collapses): the BGL counts are the mesh's
    CHECK(!out.has_garbage());
    CHECK(num_vertices(out) == b.number_of_vertices);
    CHECK(long(num_vertices(out)) - long(num_edges(out)) + long(num_faces(out)) == b.euler_characteristic);
    CHECK(b.euler_characteristic == a.euler_characteristic);
    CHECK(b.number_of_components == a.number_of_components);
    CHECK(run.number_of_leftover_input_vertices <= 2);
    CHECK(std::abs(double(b.number_of_vertices) - double(a.number_of_vertices)) <= 0.05 * a.number_of_vertices);
    CHECK(vertices_off_input(out, in) < 1e-9);
    CHECK(b.number_of_self_intersecting_face_pairs == 0);
    // better triangles than the input on average, and no worse in the worst case
    CHECK(b.mean_min_angle > 50);
    CHECK(b.mean_min_angle > a.mean_min_angle);
    CHECK(b.share_min_angle_below_30 < 0.01);
    CHECK(b.irregular_share <= 0.25);
    // issue 5's floor, met in full on these six (seed 3: knot1 35.8° / 54.4° / 18.6%; elephant
    // 35.0 / 54.2 / 22.7%; fandisk 35.0 / 52.9 / 20.8%; bull 32.3 / 54.1 / 20.9%; triceratops
    // 35.2 / 53.6 / 23.3%, Hausdorff 0.88%, and dino 34.2 / 53.6 / 23.3% with their horn and claw
    // tips sampled finer: feature grading)
    CHECK(b.mean_min_angle >= 52);
    CHECK(b.min_angle >= 30);
    REQUIRE(b.min_angle_away_from_sharp_corners);
    CHECK(*b.min_angle_away_from_sharp_corners >= b.min_angle);
    CHECK(*b.hausdorff < 0.01);
  }
}

TEST_CASE("other seeds: a crease beside another is dropped, Lloyd moves make no slivers", "[remesh][seeds]")
{
  // dino at seeds 0 and 6 had 6.8 and 6.2 degrees: along its tail two creases run 0.4 spacings
  // apart, the second one's samples were all refused and its output edge spanned 8.5 spacings;
  // on a finger, Lloyd moves lined a vertex up with two neighbours (172 degrees); at seed 5 a fan
  // folded over on a claw crossed 4 face pairs until the untangling's collapses
  Mesh in;
  PR::read_surface_mesh(test_support::data_mesh("meshes/dino.off"), in);
  for(unsigned int seed : {0u, 6u, 5u}) {
    INFO("seed " << seed);
    Mesh out;
    const auto run = PR::poisson_remesh(in, out, PR::parameters::random_seed(seed));
    CHECK(run.number_of_dropped_feature_curves >= 1);
    CHECK(longest_edge(out) < 3 * 2 * run.sampling.radius);   // 3 spacings
    const PR::Quality_report b = PR::quality_report(out, in);
    CHECK(b.min_angle >= 30);
    CHECK(b.mean_min_angle >= 52);
    CHECK(b.number_of_self_intersecting_face_pairs == 0);
    CHECK(*b.hausdorff < 0.01);
    CHECK(vertices_off_input(out, in) < 1e-9);
  }
}

TEST_CASE("the mesh stays within 1% of the input at seed 5: input points inside triangles, edges across grooves", "[remesh][seeds][fidelity]")
{
  // at seed 5 triceratops was 1.03% away (a point inside an input triangle on a horn, its
  // vertices nearer than the tolerance) and elephant 1.04% (an output edge across a groove,
  // made by the angle optimization)
  for(const char* name : {"meshes/triceratops.off", "meshes/elephant.off"}) {
    INFO(name);
    Mesh in, out;
    PR::read_surface_mesh(test_support::data_mesh(name), in);
    const auto run = PR::poisson_remesh(in, out, PR::parameters::random_seed(5u));
    CHECK(run.relaxation.fidelity_insertions > 0);
    const PR::Quality_report b = PR::quality_report(out, in);
    REQUIRE(b.hausdorff);
    CHECK(*b.hausdorff < 0.01);
    CHECK(b.min_angle >= 30);
    CHECK(b.number_of_self_intersecting_face_pairs == 0);
    CHECK(vertices_off_input(out, in) < 1e-9);
  }
}

TEST_CASE("cow: its horn tips and its input's own crossings aside, the floor holds", "[remesh][seeds][tips]")
{
  // cow's horn tips are cones of 101 degrees at the spacing: three triangles there reach 28.1
  // degrees at best, and the quality report leaves them out; the angle optimization weights the
  // tips' angles so that their neighbours raise theirs (29.13 degrees beside a tip at seed 6
  // without it). Its input cuts itself at 101 face pairs (the tail through the body): every
  // crossing of the output lies there. At seed 1, two pinned vertices of the fidelity pass on a
  // ridge beside a horn held two triangles at 29.7 degrees until they could move a little at the
  // end (the pinned vertices' polish). At seed 0, a triangle of 25.3 degrees on the tail where it
  // runs through the body: the angle moves there made crossings with the body, new ones, and were
  // taken back; crossings near the input's own no longer count as new.
  const unsigned int seed = GENERATE(6u, 1u, 0u);
  CAPTURE(seed);
  Mesh in, out;
  PR::read_surface_mesh(test_support::data_mesh("meshes/cow.off"), in);
  PR::poisson_remesh(in, out, PR::parameters::random_seed(seed));
  const PR::Quality_report b = PR::quality_report(out, in);
  REQUIRE(b.min_angle_away_from_sharp_corners);
  CHECK(b.min_angle < 30);                                   // the tips ...
  CHECK(b.number_of_angles_at_sharp_corners >= 6);           // ... two of them, three angles each
  CHECK(*b.min_angle_away_from_sharp_corners >= 30);
  CHECK(b.mean_min_angle >= 52);
  CHECK(b.irregular_share <= 0.25);
  REQUIRE(b.number_of_reference_self_intersecting_face_pairs);
  CHECK(*b.number_of_reference_self_intersecting_face_pairs == 101);
  CHECK(b.number_of_self_intersecting_face_pairs > 0);
  CHECK(*b.number_of_self_intersecting_face_pairs_away_from_reference_ones == 0);
  REQUIRE(b.hausdorff);
  CHECK(*b.hausdorff < 0.01);
  CHECK(vertices_off_input(out, in) < 1e-9);
}

TEST_CASE("femur: a crumpled input is remeshed again, finer where the result folds", "[remesh][regrading]")
{
  // femur's slice seams are pleats folded back over the surface, narrower than the spacing: the
  // first remesh cuts itself and keeps slivers at false corners; the remakes sample finer around
  // those places and keep the best result. What they promise does not depend on the draw: no
  // crossing left, the input's topology, no sliver, never worse than the first attempt. (The
  // floor of 30 degrees itself holds at some seeds only: 24.6-32.2 degrees over seeds 1-6.)
  Mesh in;
  PR::read_surface_mesh(test_support::data_mesh("meshes/femur.off"), in);
  const PR::Quality_report a = PR::quality_report(in);
  Mesh once;
  const auto first = PR::poisson_remesh(in, once, PR::parameters::random_seed(3u).regrading_attempts(0u));
  CHECK(first.number_of_regrading_attempts == 0);
  CHECK(first.crossing_pairs_left > 0);
  const PR::Quality_report o = PR::quality_report(once, in);
  CHECK(o.number_of_self_intersecting_face_pairs > 0);
  Mesh out;
  const auto run = PR::poisson_remesh(in, out, PR::parameters::random_seed(3u));
  CHECK(run.number_of_regrading_attempts >= 1);
  CHECK(run.number_of_regrading_attempts <= 6);
  CHECK(run.crossing_pairs_left == 0);
  const PR::Quality_report b = PR::quality_report(out, in);
  CHECK(CGAL::is_valid_polygon_mesh(out));
  CHECK(b.euler_characteristic == a.euler_characteristic);
  CHECK(b.number_of_components == a.number_of_components);
  CHECK(b.number_of_self_intersecting_face_pairs == 0);
  REQUIRE(b.min_angle_away_from_sharp_corners);
  REQUIRE(o.min_angle_away_from_sharp_corners);
  CHECK(*b.min_angle_away_from_sharp_corners >= *o.min_angle_away_from_sharp_corners);
  CHECK(*b.min_angle_away_from_sharp_corners >= 20);
  CHECK(run.min_angle_away_from_corners == Approx(*b.min_angle_away_from_sharp_corners));
  CHECK(b.mean_min_angle >= 52);
  CHECK(b.irregular_share <= 0.25);
  REQUIRE(b.hausdorff);
  CHECK(*b.hausdorff < 0.01);
  CHECK(vertices_off_input(out, in) < 1e-9);
  // finer only around the folds: a few more vertices (4,306-4,804 for 3,897 over seeds 1-6)
  CHECK(double(b.number_of_vertices) <= 1.3 * a.number_of_vertices);
}

TEST_CASE("remakes that do not beat the best attempt twice in a row stop, unless the best cuts itself", "[remesh][regrading]")
{
  const PR::internal::Regrading_settings settings;
  REQUIRE(settings.max_attempts_without_gain == 2);
  PR::internal::Regrading_places<Point> best;
  best.min_angle_away = 25;
  best.sharp = 3;
  CHECK_FALSE(PR::internal::remakes_stop_for_want_of_gain(0, best, settings));   // the last attempt was the best
  CHECK_FALSE(PR::internal::remakes_stop_for_want_of_gain(1, best, settings));
  CHECK(PR::internal::remakes_stop_for_want_of_gain(2, best, settings));          // twice no gain: stop
  best.crossing_pairs = 1;
  CHECK_FALSE(PR::internal::remakes_stop_for_want_of_gain(5, best, settings));   // a crossing is worth every attempt
  // boeing at its own count, seed 6: its first attempt keeps triangles under 30 degrees, and the
  // remakes stop before the sixth (the default limit: here the vertex growth limit and the
  // want-of-gain rule stop it together); the best attempt is kept
  Mesh in;
  PR::read_surface_mesh(test_support::data_mesh("meshes/boeing.off"), in);
  Mesh out;
  const auto run = PR::poisson_remesh(in, out, PR::parameters::random_seed(6u));
  CHECK(run.number_of_regrading_attempts >= 2);
  CHECK(run.number_of_regrading_attempts < 6);
  CHECK(run.crossing_pairs_left == 0);
  const PR::Quality_report b = PR::quality_report(out, in);
  CHECK(b.euler_characteristic == PR::quality_report(in).euler_characteristic);
  REQUIRE(b.min_angle_away_from_sharp_corners);
  CHECK(*b.min_angle_away_from_sharp_corners == Approx(run.min_angle_away_from_corners).margin(1e-6));
}

TEST_CASE("a fault that a new draw reproduces is not remade again", "[remesh][regrading]")
{
  // a result at fault with no place to regrade (no crossing; its triangles under 30 degrees all
  // at fixed vertices) is made again as a new draw; when that draw leaves the very same fault
  // (blade at seed 1: 10.64 degrees in each of six remakes), no remake follows
  PR::internal::Regrading_places<Point> first;
  first.min_angle_away = 10.64;
  first.sharp = 2;
  REQUIRE(first.wanted());
  CHECK(first.places.empty());
  CHECK(first.remake_wanted(nullptr));              // the first attempt: a new draw is tried
  PR::internal::Regrading_places<Point> same = first;
  CHECK_FALSE(same.remake_wanted(&first));          // the draw did not matter
  PR::internal::Regrading_places<Point> other = first;
  other.min_angle_away = 17.5;
  CHECK(other.remake_wanted(&first));               // the draw changed the fault: another one
  PR::internal::Regrading_places<Point> with_place = first;
  with_place.sharp_free = 1;
  with_place.places.push_back(Point(0, 0, 0));
  CHECK(with_place.remake_wanted(&first));          // a place to sample finer
  PR::internal::Regrading_places<Point> crossing = first;
  crossing.crossing_pairs = 1;
  crossing.places = {Point(0, 0, 0), Point(1, 0, 0)};
  CHECK(crossing.remake_wanted(&crossing));
  PR::internal::Regrading_places<Point> fine;
  fine.min_angle_away = 31;
  CHECK_FALSE(fine.wanted());
  CHECK_FALSE(fine.remake_wanted(nullptr));
}

TEST_CASE("of two creases closer than the spacing, the output keeps one", "[remesh][features]")
{
  // a step across a plane: two creases of 63 degrees along y, 0.11 apart, at a spacing of 0.2
  analytic::Soup soup = analytic::plane(40, 40);
  for(auto& p : soup.points) p[2] = p[0] <= 0.45 ? 0.0 : p[0] >= 0.5 - 1e-12 ? 0.1 : 0.1 * (p[0] - 0.45) / 0.05;
  const Mesh in = soup.to_mesh<Mesh>();
  Mesh out;
  // (no remakes: the rule is the first draw's; a remake samples finer)
  const auto run = PR::poisson_remesh(in, out, PR::parameters::sampling_radius(0.1).random_seed(1u).regrading_attempts(0u));
  // the creases were features (8 corners: the plane's four and the four where the creases meet
  // the border) ...
  REQUIRE(run.sampling.number_of_corners == 8);
  // ... and the one sampled second, all its samples refused, is no feature of the output
  CHECK(run.number_of_dropped_feature_curves == 1);
  CHECK(CGAL::is_valid_polygon_mesh(out));
  const PR::Quality_report a = PR::quality_report(in), b = PR::quality_report(out, in);
  CHECK(b.euler_characteristic == a.euler_characteristic);
  CHECK(vertices_off_input(out, in) < 1e-9);
  CHECK(longest_edge(out) < 0.6);   // 3 spacings (the longest are border edges beside the corners, 0.46)
}

TEST_CASE("remeshing is deterministic for a given seed", "[remesh]")
{
  Mesh in, a, b;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elephant.off"), in);
  PR::poisson_remesh(in, a, PR::parameters::target_vertex_count(800).random_seed(5u));
  PR::poisson_remesh(in, b, PR::parameters::target_vertex_count(800).random_seed(5u));
  REQUIRE(num_vertices(a) == num_vertices(b));
  auto vb = vertices(b).begin();
  for(auto v : vertices(a)) CHECK(a.point(v) == b.point(*vb++));
}

#ifdef CGAL_LINKED_WITH_TBB
TEST_CASE("the parallel relaxation gives the sequential output, and the parallel mode one output whatever the number of threads", "[remesh][parallel]")
{
  // (the same points and the same faces: the parallel vertex passes move, at once, vertices whose
  // earlier neighbours have moved; the parallel mode samples by slabs, another maximal set than
  // the sequential sampler's, so the sequential one is given to both as a user's sampler)
  auto same = [](const Mesh& a, const Mesh& b) {
    REQUIRE(num_vertices(a) == num_vertices(b));
    REQUIRE(num_faces(a) == num_faces(b));
    auto vb = vertices(b).begin();
    std::size_t moved = 0;
    for(auto v : vertices(a)) if(a.point(v) != b.point(*vb++)) ++moved;
    CHECK(moved == 0);
    auto fb = faces(b).begin();
    std::size_t other = 0;
    for(auto f : faces(a)) {
      std::vector<std::size_t> x, y;
      for(auto v : CGAL::vertices_around_face(halfedge(f, a), a)) x.push_back(std::size_t(v));
      for(auto v : CGAL::vertices_around_face(halfedge(*fb, b), b)) y.push_back(std::size_t(v));
      ++fb;
      if(x != y) ++other;
    }
    CHECK(other == 0);
  };
  for(const bool adaptive : {false, true}) {
    INFO((adaptive ? "adaptive" : "uniform"));
    Mesh in, sequential;
    PR::read_surface_mesh(test_support::data_mesh(adaptive ? "meshes/elephant.off" : "meshes/fandisk.off"), in);
    auto np = PR::parameters::target_vertex_count(1200).random_seed(2u).sampler(PR::Poisson_disk_sampler());
    if(adaptive) PR::poisson_remesh(in, sequential, np.density(PR::Curvature_density()));
    else PR::poisson_remesh(in, sequential, np);
    for(const int threads : {1, 2, 4}) {
      INFO(threads << " threads");
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
      Mesh parallel;
      if(adaptive) PR::poisson_remesh<CGAL::Parallel_tag>(in, parallel, np.density(PR::Curvature_density()));
      else PR::poisson_remesh<CGAL::Parallel_tag>(in, parallel, np);
      same(sequential, parallel);
    }
  }
  // the whole parallel mode (slab sampling too): one output for 1, 2 and 4 threads
  {
    Mesh in, one;
    PR::read_surface_mesh(test_support::data_mesh("meshes/camel.off"), in);
    const auto np = PR::parameters::target_vertex_count(3000).random_seed(4u);
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(1));
      PR::poisson_remesh<CGAL::Parallel_tag>(in, one, np);
    }
    for(const int threads : {2, 4}) {
      INFO(threads << " threads, whole parallel mode");
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
      Mesh parallel;
      PR::poisson_remesh<CGAL::Parallel_tag>(in, parallel, np);
      same(one, parallel);
    }
  }
  // the rounds behind it: every vertex in one, after the rounds of its neighbours earlier in the
  // order and before those of its neighbours later in it
  Mesh m;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elephant.off"), m);
  std::vector<Mesh::Vertex_index> order(vertices(m).begin(), vertices(m).end());
  std::reverse(order.begin(), order.end());   // (any order: here the reverse of the mesh's)
  const auto rounds = PR::internal::dependency_rounds(m, order);
  std::vector<int> round_of(num_vertices(m), -1), rank(num_vertices(m), -1);
  for(std::size_t i = 0; i < order.size(); ++i) rank[std::size_t(order[i])] = int(i);
  for(std::size_t r = 0; r < rounds.size(); ++r)
    for(auto v : rounds[r]) { CHECK(round_of[std::size_t(v)] == -1); round_of[std::size_t(v)] = int(r); }
  std::size_t misplaced = 0;
  for(auto e : edges(m)) {
    std::size_t a = std::size_t(source(e, m)), b = std::size_t(target(e, m));
    if(rank[a] > rank[b]) std::swap(a, b);
    if(!(round_of[a] >= 0 && round_of[a] < round_of[b])) ++misplaced;
  }
  CHECK(misplaced == 0);
  CHECK(std::count(round_of.begin(), round_of.end(), -1) == 0);
  CHECK(rounds.size() < num_vertices(m) / 10);   // (rounds of many vertices: the point of them)
}
#endif

TEST_CASE("pointed tips are sampled finer, graded back to the spacing; needles are left alone", "[remesh][grading]")
{
  SECTION("triceratops: its horn tips are thinner than the spacing") {
    Mesh in;
    PR::read_surface_mesh(test_support::data_mesh("meshes/triceratops.off"), in);
    const double r = PR::internal::sampling_radius_from_parameters(in, in.points(), PR::parameters::default_values());
    const auto features = PR::internal::detect_features_at_radius(in, r, PR::parameters::default_values());
    std::size_t tips = 0;
    const std::vector<double> radii = PR::internal::feature_graded_radii(in, in.points(), features, r, tips);
    CHECK(tips >= 2);   // the two horns at least
    REQUIRE(radii.size() == num_vertices(in));
    double smallest = r;
    for(double x : radii) { CHECK(x <= r); smallest = std::min(smallest, x); }
    CHECK(smallest >= 0.125 * r);   // the floor of the grading
    CHECK(smallest < 0.5 * r);
    // the radius grows by at most 1/4 per unit of length along each edge
    for(auto e : edges(in)) {
      const auto a = source(halfedge(e, in), in), b = target(halfedge(e, in), in);
      const double length = std::sqrt(CGAL::to_double(CGAL::squared_distance(in.point(a), in.point(b))));
      CHECK(std::abs(radii[a.idx()] - radii[b.idx()]) <= 0.25 * length + 1e-12);
    }
    // the remesh reports them, and at seed 2 its smallest angle is over 30 degrees (16.2 without)
    Mesh out;
    const auto run = PR::poisson_remesh(in, out, PR::parameters::random_seed(2u));
    CHECK(run.number_of_graded_tips == tips);
    const PR::Quality_report q = PR::quality_report(out, in);
    CHECK(q.min_angle >= 30);
    CHECK(q.number_of_self_intersecting_face_pairs == 0);
    CHECK(q.irregular_share <= 0.25);
  }
  SECTION("a needle (a sphere's pole pulled out into a spike, angle sum 23 degrees) is not graded: same output") {
    analytic::Soup s = analytic::sphere(32, 16);
    std::size_t top = 0;
    for(std::size_t i = 0; i < s.points.size(); ++i) if(s.points[i][2] > s.points[top][2]) top = i;
    s.points[top][2] = 4;
    const Mesh in = s.to_mesh<Mesh>();
    // the pole is a tip, and only the needle rule leaves it alone
    const double r = PR::internal::sampling_radius_from_parameters(in, in.points(), PR::parameters::target_vertex_count(600));
    const auto features = PR::internal::detect_features_at_radius(in, r, PR::parameters::target_vertex_count(600));
    REQUIRE(features.corners.size() == 1);
    std::size_t tips = 0;
    CHECK(PR::internal::feature_graded_radii(in, in.points(), features, r, tips).empty());
    CHECK(tips == 0);
    PR::internal::Feature_grading_settings no_needles;
    no_needles.needle_angle = 0;
    CHECK(!PR::internal::feature_graded_radii(in, in.points(), features, r, tips, no_needles).empty());
    CHECK(tips == 1);
    Mesh a, b;
    const auto run = PR::poisson_remesh(in, a, PR::parameters::target_vertex_count(600).random_seed(1u));
    PR::poisson_remesh(in, b, PR::parameters::target_vertex_count(600).random_seed(1u).feature_grading(false));
    CHECK(run.number_of_graded_tips == 0);
    REQUIRE(num_vertices(a) == num_vertices(b));
    auto vb = vertices(b).begin();
    for(auto v : vertices(a)) CHECK(a.point(v) == b.point(*vb++));
  }
}

TEST_CASE("the Lloyd relaxer improves a mesh and keeps it on the input", "[remesh][relaxer]")
{
  const Mesh in = analytic::sphere(40, 20).to_mesh<Mesh>();  // skinny triangles at the poles
  Mesh m = in;
  const auto features = PR::detect_features(in);
  PR::Lloyd_relaxer<Mesh, K> relaxer(in, features);
  const auto stats = relaxer.relax(m, [](Mesh::Edge_index) { return false; }, [](Mesh::Vertex_index) { return false; });
  const PR::Quality_report before = PR::quality_report(in), after = PR::quality_report(m, in);
  CHECK(stats.moves > 0);
  CHECK(after.mean_min_angle > before.mean_min_angle);
  CHECK(after.min_angle > before.min_angle);
  CHECK(after.euler_characteristic == 2);
  CHECK(after.number_of_self_intersecting_face_pairs == 0);
  CHECK(vertices_off_input(m, in) < 1e-9);
}

TEST_CASE("the whole remesher runs on Polyhedron_3 and keeps a cube's corners and topology", "[remesh][polyhedron]")
{
  typedef CGAL::Polyhedron_3<K, CGAL::Polyhedron_items_with_id_3> Polyhedron;
  Polyhedron in = analytic::cube(6).to_mesh<Polyhedron>();
  CGAL::set_halfedgeds_items_id(in);
  Polyhedron out;
  const auto run = PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(600).random_seed(4u));
  const PR::Quality_report q = PR::quality_report(out, in);
  CHECK(CGAL::is_valid_polygon_mesh(out));
  CHECK(CGAL::is_closed(out));
  CHECK(q.euler_characteristic == 2);
  CHECK(run.number_of_leftover_input_vertices == 0);
  CHECK(q.number_of_self_intersecting_face_pairs == 0);
  CHECK(*q.hausdorff <= 1.5e-4);   // a cube is kept exactly (the measure's error bound is 1e-4)
  CHECK(q.min_angle > 30);
  CHECK(q.mean_min_angle > 50);
  std::size_t corners = 0;
  for(auto v : vertices(out)) {
    const Point p = v->point();
    if(std::abs(std::abs(p.x() - 0.5) - 0.5) < 1e-12 && std::abs(std::abs(p.y() - 0.5) - 0.5) < 1e-12 &&
       std::abs(std::abs(p.z() - 0.5) - 0.5) < 1e-12) ++corners;
  }
  CHECK(corners == 8);
}

TEST_CASE("a tetrahedron is remeshed along its six creases: about the vertices asked for, no triangle under 30 degrees", "[remesh][features]")
{
  // every face of a tetrahedron is one triangle whose three edges are creases (see the features
  // test of coarse polyhedra); when they were lost, 50 vertices asked gave 1,753 and a smallest
  // angle of 4.8 degrees (and minutes of repair)
  std::vector<Point> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  std::vector<std::vector<std::size_t>> polygons = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  Mesh in;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, in);
  for(const std::size_t asked : {std::size_t(50), std::size_t(300)}) {
    INFO("asked " << asked);
    Mesh out;
    PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(asked).random_seed(1u));
    CHECK(double(num_vertices(out)) > 0.75 * double(asked));
    CHECK(double(num_vertices(out)) < 1.25 * double(asked));
    CHECK(CGAL::is_closed(out));
    CHECK(vertices_off_input(out, in) < 1e-9);
    // the smallest angle, computed by the test itself
    CHECK(smallest_angle_degrees(out) >= 30);
    // the corners kept, and every edge of the output that lies along a crease of the tetrahedron
    // (both ends on one of its edges) makes the creases' whole length
    std::size_t corners = 0;
    for(auto v : vertices(out))
      for(const Point& c : points) if(CGAL::squared_distance(out.point(v), c) < 1e-24) ++corners;
    CHECK(corners == 4);
    auto on_segment = [](const Point& x, const Point& a, const Point& b) {
      return CGAL::squared_distance(x, K::Segment_3(a, b)) < 1e-20;
    };
    double along = 0;
    for(auto e : edges(out)) {
      const Point a = out.point(source(halfedge(e, out), out)), b = out.point(target(halfedge(e, out), out));
      for(std::size_t i = 0; i < 4; ++i)
        for(std::size_t j = i + 1; j < 4; ++j)
          if(on_segment(a, points[i], points[j]) && on_segment(b, points[i], points[j])) along += std::sqrt(CGAL::to_double(CGAL::squared_distance(a, b)));
    }
    CHECK(along == Approx(3 + 3 * std::sqrt(2.)).epsilon(1e-9));
  }
}

TEST_CASE("the fidelity splits along a curve make no flat triangle (elk at three times its count)", "[remesh][fidelity]")
{
  // a chord of a feature curve split at the curve's point nearest its midpoint, when that point
  // lay on the straight input edge from an end of the chord to the opposite vertex, made a flat
  // triangle (4.5e-15 degrees) that no move along the curve could open
  Mesh in;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elk.off"), in);
  Mesh out;
  PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(3 * num_vertices(in)).random_seed(1u));
  CHECK(smallest_angle_degrees(out) > 10);
  CHECK(CGAL::is_closed(out));
}

TEST_CASE("the remakes (regrading) run on Polyhedron_3 too, the same in every run of a seed", "[remesh][polyhedron][regrading][determinism]")
{
  // femur folds at every seed the first time (RESULTS.md, Development notes: remakes): the remakes copy the best result
  // aside with copy_face_graph, and free corners through the kind map. The items have ids, and the
  // relaxer adds and removes vertices: a new vertex may take the memory of a removed one, and so
  // its descriptor; what the maps held for that one must not carry over (its density did: the
  // remesh differed from run to run). The heap is left full of holes between the two runs, so
  // that the second run's elements lie elsewhere.
  typedef CGAL::Polyhedron_3<K, CGAL::Polyhedron_items_with_id_3> Polyhedron;
  Polyhedron in;
  PR::read_surface_mesh(test_support::data_mesh("meshes/femur.off"), in);
  CGAL::set_halfedgeds_items_id(in);
  std::vector<std::vector<K::Point_3>> points;
  std::vector<std::unique_ptr<char[]>> holes;
  for(int run = 0; run < 2; ++run) {
    Polyhedron out;
    const auto result = PR::poisson_remesh(in, out, PR::parameters::random_seed(1u));
    points.emplace_back();
    for(auto v : vertices(out)) points.back().push_back(v->point());
    for(int i = 0; i < 20000; ++i) holes.emplace_back(new char[16 + (i * 7919) % 400]);
    for(std::size_t i = 0; i < holes.size(); i += 2) holes[i].reset();
    if(run > 0) continue;
    CHECK(result.number_of_regrading_attempts >= 1);
    const PR::Quality_report a = PR::quality_report(in), b = PR::quality_report(out, in);
    CHECK(CGAL::is_valid_polygon_mesh(out));
    CHECK(b.euler_characteristic == a.euler_characteristic);
    REQUIRE(b.number_of_self_intersecting_face_pairs_away_from_reference_ones);
    CHECK(*b.number_of_self_intersecting_face_pairs_away_from_reference_ones == result.crossing_pairs_left);
    REQUIRE(b.min_angle_away_from_sharp_corners);
    CHECK(result.min_angle_away_from_corners == Approx(*b.min_angle_away_from_sharp_corners));
    CHECK(b.mean_min_angle >= 52);
    REQUIRE(b.hausdorff);
    CHECK(*b.hausdorff < 0.01);
  }
  CHECK(points[1] == points[0]);
}

namespace {
// a model of the Relaxer concept that only counts its calls (and leaves the tessellation as it is)
struct Counting_relaxer
{
  int* calls;
  template <class In, class InVPM, class M, class F, class X, class D, class N>
  PR::Relaxation_statistics relax(const In&, InVPM, M&, F, X, D, unsigned int iterations, N) const
  {
    ++*calls;
    CHECK(iterations == 2u);   // number_of_iterations reaches the relaxer
    return {};
  }
};
} // namespace

TEST_CASE("a user's Relaxer is used through the relaxer named parameter", "[remesh][relaxer]")
{
  Mesh in, relaxed, plain;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elephant.off"), in);
  int calls = 0;
  PR::poisson_remesh(in, plain, PR::parameters::target_vertex_count(800).random_seed(5u)
                                   .relaxer(Counting_relaxer{&calls}).number_of_iterations(2u));
  PR::poisson_remesh(in, relaxed, PR::parameters::target_vertex_count(800).random_seed(5u).number_of_iterations(2u));
  CHECK(calls == 1);
  const PR::Quality_report a = PR::quality_report(plain, PR::parameters::check_self_intersections(false));
  const PR::Quality_report b = PR::quality_report(relaxed, PR::parameters::check_self_intersections(false));
  // unrelaxed: the mutual tessellation itself (Delaunay-like, mean smallest angle about 45)
  CHECK(a.mean_min_angle < 47);
  CHECK(b.mean_min_angle > a.mean_min_angle + 3);
  CHECK(a.euler_characteristic == b.euler_characteristic);
}

// ------------------------------------------------------------------ imperfect but valid input (issue 7)

namespace {
// every point scaled by s about the origin
Mesh scaled(const Mesh& m, double s)
{
  Mesh out = m;
  for(auto v : vertices(out)) out.point(v) = Point(s * m.point(v).x(), s * m.point(v).y(), s * m.point(v).z());
  return out;
}
// the soups of `parts` in one soup, the i-th moved by offsets[i] along x
analytic::Soup merged(const std::vector<analytic::Soup>& parts, const std::vector<double>& offsets)
{
  analytic::Soup s;
  for(std::size_t i = 0; i < parts.size(); ++i) {
    const std::size_t base = s.points.size();
    for(auto p : parts[i].points) { p[0] += offsets[i]; s.points.push_back(p); }
    for(auto t : parts[i].triangles) { for(auto& k : t) k += base; s.triangles.push_back(t); }
  }
  return s;
}
} // namespace

TEST_CASE("the relaxer's local self-intersection check finds what a whole-mesh check finds", "[remesh][relaxer]")
{
  // two overlapping spheres in one mesh: crossings there already, away from the vertex that moves
  Mesh m = merged({analytic::sphere(30, 15), analytic::sphere(30, 15)}, {0, 1.5}).to_mesh<Mesh>();
  typedef Mesh::Face_index F;
  auto whole = [&] {
    std::vector<std::pair<F, F>> pairs;
    CGAL::Polygon_mesh_processing::self_intersections(m, std::back_inserter(pairs));
    for(auto& fp : pairs) if(fp.second < fp.first) std::swap(fp.first, fp.second);
    std::sort(pairs.begin(), pairs.end());
    return pairs;
  };
  const auto before = whole();
  REQUIRE(!before.empty());
  // the first sphere's vertex farthest from the second, pushed through its own sphere
  Mesh::Vertex_index v = *vertices(m).begin();
  for(auto w : vertices(m)) if(m.point(w).x() < m.point(v).x()) v = w;
  const std::vector<Mesh::Vertex_index> moved{v};
  const auto changed = PR::internal::faces_around(m, moved);
  CHECK(changed.size() == degree(v, m));
  CHECK(PR::internal::intersecting_pairs_near(m, changed).empty());   // nothing near it crosses yet
  m.point(v) = Point(0.8, 0.05, 0.02);
  const auto after = whole();
  const auto near = PR::internal::intersecting_pairs_near(m, changed);
  auto involves_changed = [&](const std::pair<F, F>& fp) {
    return std::binary_search(changed.begin(), changed.end(), fp.first) || std::binary_search(changed.begin(), changed.end(), fp.second);
  };
  std::size_t new_pairs = 0;
  for(const auto& fp : after) {
    if(std::binary_search(before.begin(), before.end(), fp)) continue;
    ++new_pairs;
    CHECK(involves_changed(fp));                                      // only the moved faces cross anew
    CHECK(std::binary_search(near.begin(), near.end(), fp));          // and the local check finds each
  }
  CHECK(new_pairs > 0);
  for(const auto& fp : near) CHECK(std::binary_search(after.begin(), after.end(), fp));   // nothing it invents
}

TEST_CASE("the relaxer's untangling removes a crossing made by a vertex pushed through another sheet", "[remesh][relaxer]")
{
  // two overlapping spheres (crossings in the input itself); a vertex of the first pushed into
  // the second crosses it anew: the untangling moves it back (toward its neighbours, on the
  // input); of the input's own crossings none is added
  const Mesh in = merged({analytic::sphere(30, 15), analytic::sphere(30, 15)}, {0, 1.5}).to_mesh<Mesh>();
  const auto features = PR::detect_features(in);
  PR::Lloyd_relaxer<Mesh, K> relaxer(in, features);
  Mesh::Vertex_index v = *vertices(in).begin();
  for(auto w : vertices(in)) if(in.point(w).x() < in.point(v).x()) v = w;
  auto pairs_of = [](const Mesh& m) {
    std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
    CGAL::Polygon_mesh_processing::self_intersections(m, std::back_inserter(pairs));
    return pairs;
  };
  auto crossings = [&](const Mesh& m) { return pairs_of(m).size(); };
  const std::size_t own = crossings(in);
  REQUIRE(own > 0);
  PR::Relaxation_settings s;   // everything off but the last Lloyd pass, its Delaunay flips and the untangling
  s.iterations = 0;
  s.sliver_collapse.enabled = false;
  s.fidelity.max_deviation = 0;
  s.angle_smoothing.rounds = s.regularity.rounds = s.angle_optimization.rounds = s.refinement.rounds = 0;
  s.delaunay_flips = false;
  for(unsigned int rounds : {0u, 3u}) {
    INFO("untangle rounds " << rounds);
    Mesh m = in;
    m.point(v) = Point(0.8, 0.05, 0.02);
    REQUIRE(crossings(m) > own);
    s.untangling.rounds = rounds;
    const auto stats = relaxer.relax(m, [](Mesh::Edge_index) { return false; }, [&](Mesh::Vertex_index x) { return x != v; }, s);
    if(rounds == 0) {
      CHECK(crossings(m) > own);
    } else {
      CHECK(crossings(m) <= own);   // (its flips may mend some of the input's too)
      const auto mine = PR::internal::faces_around(m, std::vector<Mesh::Vertex_index>{v});
      for(const auto& fp : pairs_of(m))   // none left at the vertex pushed through
        CHECK(!(std::binary_search(mine.begin(), mine.end(), fp.first) || std::binary_search(mine.begin(), mine.end(), fp.second)));
      CHECK(stats.untangle_changes > 0);
      CHECK(vertices_off_input(m, in) < 1e-9);
    }
  }
}

TEST_CASE("remeshing does not depend on the size of the coordinates (1e-6 to 1e6)", "[remesh][robustness]")
{
  Mesh in;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elephant.off"), in);
  // (without the remakes: at 1000 vertices the first remesh crosses itself at 3 face pairs, and
  // whether round-off leaves a remake one more place to refine is a discrete outcome)
  Mesh ref;
  PR::poisson_remesh(in, ref, PR::parameters::target_vertex_count(1000).random_seed(6u).regrading_attempts(0u));
  const PR::Quality_report qr = PR::quality_report(ref, in);
  for(double s : {1e-6, 1e6}) {
    INFO("scale " << s);
    const Mesh big = scaled(in, s);
    Mesh out;
    PR::poisson_remesh(big, out, PR::parameters::target_vertex_count(1000).random_seed(6u).regrading_attempts(0u));
    const PR::Quality_report q = PR::quality_report(out, big);
    // tolerances are relative to the mesh, so the result is the same kind of mesh; round-off
    // changes some decisions (a sample a few ulps inside or outside a disk), and so the draw, not
    // its quality (from one draw to another at this count the mean smallest angle moves by up to
    // 1.4 degrees: 50.97 to 52.39 over seeds 6-9 at the three sizes, this library or the last)
    CHECK(std::abs(double(q.number_of_vertices) - double(qr.number_of_vertices)) <= 0.02 * double(qr.number_of_vertices));
    CHECK(q.euler_characteristic == qr.euler_characteristic);
    CHECK(std::abs(q.mean_min_angle - qr.mean_min_angle) < 1.5);
    CHECK(q.mean_min_angle > 51);
    // (the Hausdorff distance, a maximum over the surface, is set by one place: at this count it
    // moves by up to 40% from one draw to another, 1.40% to 1.96% of the diagonal over seeds 1-12
    // at both sizes)
    CHECK(*q.hausdorff < 1.4 * *qr.hausdorff + 1e-3);
    CHECK(q.number_of_self_intersecting_face_pairs == 0);
  }
}

TEST_CASE("several components, tiny ones included, and an open mesh with three borders are remeshed", "[remesh][robustness]")
{
  SECTION("a sphere, a torus and a sphere 50 times smaller") {
    const Mesh in = merged({analytic::sphere(40, 20), analytic::torus(48, 16), analytic::sphere(12, 6, 0.02)}, {0, 5, -3})
                      .to_mesh<Mesh>();
    Mesh out;
    const auto run = PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(1500).random_seed(2u));
    const PR::Quality_report a = PR::quality_report(in), b = PR::quality_report(out, in);
    CHECK(b.number_of_components == 3);   // the tiny sphere gets a seed of its own
    CHECK(b.euler_characteristic == a.euler_characteristic);
    CHECK(CGAL::is_closed(out));
    CHECK(run.number_of_leftover_input_vertices <= 8);   // the tiny sphere is far under the sample spacing
    CHECK(b.mean_min_angle > 50);
    CHECK(b.number_of_self_intersecting_face_pairs == 0);
  }
  SECTION("a square with two round holes: three borders kept as features") {
    analytic::Soup s = analytic::plane(40, 40);
    std::vector<std::vector<std::size_t>> kept;
    for(const auto& t : s.triangles) {
      double cx = 0, cy = 0;
      for(auto k : t) { cx += s.points[k][0] / 3; cy += s.points[k][1] / 3; }
      const bool in_hole = std::hypot(cx - 0.3, cy - 0.3) < 0.12 || std::hypot(cx - 0.7, cy - 0.65) < 0.15;
      if(!in_hole) kept.push_back(t);
    }
    s.triangles = kept;
    // (the grid points inside the holes stay in the mesh as isolated vertices: they are ignored)
    const Mesh in = s.to_mesh<Mesh>();
    std::size_t isolated = 0;
    for(auto v : vertices(in)) if(halfedge(v, in) == Mesh::null_halfedge()) ++isolated;
    REQUIRE(isolated > 0);
    Mesh out;
    PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(800).random_seed(2u));
    const PR::Quality_report a = PR::quality_report(in), b = PR::quality_report(out, in);
    REQUIRE(a.number_of_border_cycles == 3);
    CHECK(b.number_of_border_cycles == 3);
    CHECK(b.euler_characteristic == 1 - 2);   // a disk with two holes
    CHECK(b.euler_characteristic == a.euler_characteristic - long(isolated));
    CHECK(b.mean_min_angle > 50);
    CHECK(b.min_angle > 20);
    // the borders are kept up to the staircase of the holes' borders (one grid step, 1/40, is
    // 1.77% of the diagonal): measured 1.77%
    CHECK(*b.hausdorff < 0.025);
  }
}

TEST_CASE("marching-cubes output and a surface of genus 16 are remeshed", "[remesh][robustness]")
{
  // Both extracted from implicit functions on a grid (analytic::iso_surface): needles and caps down
  // to a fraction of a degree, near-coincident vertices, valences 3 to 12.
  auto check = [](const Mesh& in, std::size_t target, long chi, double min_hausdorff_bound) {
    const PR::Quality_report a = PR::quality_report(in);
    REQUIRE(CGAL::is_closed(in));
    REQUIRE(a.euler_characteristic == chi);
    CHECK(a.min_angle < 1);         // the input really is marching-cubes-like
    CHECK(a.mean_min_angle < 31);
    Mesh out;
    const auto run = PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(target).random_seed(1u));
    const PR::Quality_report b = PR::quality_report(out, in);
    CHECK(CGAL::is_closed(out));
    CHECK(b.number_of_components == 1);
    CHECK(b.euler_characteristic == chi);
    CHECK(run.number_of_leftover_input_vertices == 0);
    CHECK(std::abs(double(b.number_of_vertices) - double(target)) < 0.05 * double(target));
    CHECK(b.min_angle >= 30);       // measured 37.3 (torus), 34.8 (genus 16)
    CHECK(b.mean_min_angle > 52);   // 53.2, 52.7
    CHECK(b.irregular_share <= 0.26); // 21.2%, 25.3%
    CHECK(*b.hausdorff < min_hausdorff_bound); // 0.30%, 0.66%
    CHECK(b.number_of_self_intersecting_face_pairs == 0);
    CHECK(vertices_off_input(out, in) < 1e-9);
  };
  SECTION("a torus from a 30^3 grid") {
    auto f = [](double x, double y, double z) { const double q = std::sqrt(x * x + y * y) - 1.0; return q * q + z * z - 0.16; };
    check(analytic::iso_surface(f, -1.6, 1.6, 30).to_mesh<Mesh>(), 1500, 0, 0.006);
  }
  SECTION("a plate with 4 x 4 holes (genus 16) from a 60^3 grid") {
    auto f = [](double x, double y, double z) {
      double v = (z / 0.12) * (z / 0.12) + std::pow(x / 1.25, 8) + std::pow(y / 1.25, 8) - 1;
      for(double cx : {-0.75, -0.25, 0.25, 0.75})
        for(double cy : {-0.75, -0.25, 0.25, 0.75}) v += 2 * std::exp(-((x - cx) * (x - cx) + (y - cy) * (y - cy)) / 0.0225);
      return v;
    };
    check(analytic::iso_surface(f, -1.4, 1.4, 60).to_mesh<Mesh>(), 3000, 2 - 2 * 16, 0.01);
  }
}

TEST_CASE("a mesh whose triangles each have their own corners is merged and remeshed", "[remesh][robustness][read]")
{
  const auto dir = test_support::scratch_dir("duplicated_vertices");
  SECTION("a sphere written as 3 points per triangle") {
    const analytic::Soup s = analytic::sphere(40, 20);
    std::ostringstream off;
    off.precision(17);
    off << "OFF\n" << 3 * s.triangles.size() << " " << s.triangles.size() << " 0\n";
    for(const auto& t : s.triangles)
      for(auto k : t) off << s.points[k][0] << " " << s.points[k][1] << " " << s.points[k][2] << "\n";
    for(std::size_t f = 0; f < s.triangles.size(); ++f) off << "3 " << 3 * f << " " << 3 * f + 1 << " " << 3 * f + 2 << "\n";
    Mesh in;
    const PR::Read_report rr = PR::read_surface_mesh(test_support::write_text(dir / "soup.off", off.str()), in);
    CHECK(rr.merged_duplicate_points == 3 * s.triangles.size() - s.points.size());
    CHECK(rr.unmerged_duplicate_points == 0);
    REQUIRE(num_vertices(in) == s.points.size());
    REQUIRE(CGAL::is_closed(in));
    Mesh out;
    PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(800).random_seed(1u));
    const PR::Quality_report b = PR::quality_report(out, in);
    CHECK(b.number_of_components == 1);
    CHECK(b.euler_characteristic == 2);
    CHECK(CGAL::is_closed(out));
    CHECK(b.min_angle >= 30);
    CHECK(b.mean_min_angle > 52);
    CHECK(b.number_of_self_intersecting_face_pairs == 0);
  }
  SECTION("a torus with every other face turned over: reoriented, then remeshed") {
    const analytic::Soup s = analytic::torus(48, 16);
    std::ostringstream off;
    off.precision(17);
    off << "OFF\n" << s.points.size() << " " << s.triangles.size() << " 0\n";
    for(const auto& p : s.points) off << p[0] << " " << p[1] << " " << p[2] << "\n";
    for(std::size_t f = 0; f < s.triangles.size(); ++f) {
      const auto& t = s.triangles[f];
      if(f % 2) off << "3 " << t[0] << " " << t[2] << " " << t[1] << "\n";
      else off << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    }
    Mesh in;
    const PR::Read_report rr = PR::read_surface_mesh(test_support::write_text(dir / "flipped.off", off.str()), in);
    CHECK(rr.reoriented);
    REQUIRE(CGAL::is_closed(in));
    Mesh out;
    PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(900).random_seed(1u));
    const PR::Quality_report b = PR::quality_report(out, in);
    CHECK(b.number_of_components == 1);
    CHECK(b.euler_characteristic == 0);
    CHECK(CGAL::is_closed(out));
    CHECK(b.min_angle >= 30);
    CHECK(b.mean_min_angle > 52);
    CHECK(b.number_of_self_intersecting_face_pairs == 0);
  }
  SECTION("duplicates whose merge would pinch the surface are kept apart") {
    // two tetrahedra touching at the origin, each with its own copy of that point
    const std::string two = "OFF\n8 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n-1 0 0\n0 -1 0\n0 0 -1\n"
                            "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n3 4 5 6\n3 4 7 5\n3 5 7 6\n3 4 6 7\n";
    Mesh m;
    const PR::Read_report rr = PR::read_surface_mesh(test_support::write_text(dir / "pinch.off", two), m);
    CHECK(rr.merged_duplicate_points == 0);
    CHECK(rr.unmerged_duplicate_points == 1);
    CHECK(num_vertices(m) == 8);
    CHECK(PR::quality_report(m).number_of_components == 2);
    CHECK(!rr.warnings.empty());
  }
}

TEST_CASE("samples inside nearly zero-area input faces do not stop the tessellation (fuzz finds)", "[remesh][robustness][adaptive]")
{
  // two inputs of the pipeline fuzzer: a folded strip with a face whose three corners are
  // collinear up to rounding (two samples fall on one vertex: merged), a patch with two
  // coincident points (no sub-face of the sample's face has an area: its closest vertex is used),
  // and a face of three collinear points where the uniform sampler's arc gave no finite point
  // (the arc is dropped), and two that took minutes
  struct Case { const char* off; std::size_t target; unsigned int seed, smoothing; bool adaptive = true; };
  const Case cases[] = {
    {"OFF\n9 7 0\n0 0 -0.040392156862745103\n0.5 0 -0.015294117647058826\n1 0 0.0098039215686274613\n"
     "1 0 0.0098039215686274613\n0.5 0.5 0.0098039215686274613\n1 0.5 0.0098039215686274613\n0 1 0.0098039215686274613\n"
     "0.5 1 -0.015294117647058826\n1 1 -0.015294117647058826\n"
     "3 0 1 3\n3 1 4 3\n3 1 2 4\n3 2 5 4\n3 4 7 6\n3 4 5 7\n3 5 8 7\n", 35, 147, 3},
    {"OFF\n9 8 0\n0.074999999999999997 -0.039705882352941174 -0.052941176470588241\n"
     "-0.039705882352941174 0.96029411764705885 -0.052941176470588241\n0.96029411764705885 -0.039705882352941174 -0.052941176470588241\n"
     "-0.039705882352941174 0.46029411764705885 -0.052941176470588241\n0.46029411764705885 0.46029411764705885 -0.052941176470588241\n"
     "0.96029411764705885 0.46029411764705885 -0.052941176470588241\n-0.039705882352941174 0.96029411764705885 -0.052941176470588241\n"
     "0.46029411764705885 0.96029411764705885 -0.052941176470588241\n0.96029411764705885 0.96029411764705885 -0.052941176470588241\n"
     "3 0 1 3\n3 1 4 3\n3 1 2 4\n3 2 5 4\n3 3 4 6\n3 4 7 6\n3 4 5 7\n3 5 8 7\n", 80, 60, 0},
    {"OFF\n9 5 0\n0 0 -0.040392156862745103\n0.5 0 -0.015294117647058826\n1 0 0.0098039215686274613\n"
     "0.5 0.5 0.0098039215686274613\n1 0.5 0.0098039215686274613\n0 1 0.0098039215686274613\n0.5 1 -0.015294117647058826\n"
     "1 1 -0.015294117647058826\n0.5 0.5 0.0098039215686274613\n"
     "3 0 1 2\n3 1 3 2\n3 8 6 5\n3 8 4 6\n3 4 7 6\n", 35, 147, 0, false},
    // two needles folded onto each other: ~800 samples cut each other everywhere (the repairs
    // that look for self-intersections stop early instead of taking minutes)
    {"OFF\n4 2 0\n0.85747957022652077 -0.27336566471329449 -0.04911764705882353\n"
     "0.85747957022652066 -0.2733656647132946 0.45088235294117646\n0.8582268291112497 -0.273603891872086 0.45088235294117646\n"
     "-0.85747957022652077 0.27336566471329454 0.45088235294117646\n3 1 0 2\n3 1 2 3\n", 20, 0, 0},
    // a flat double-sided sheet (a closed mesh of two coincident pairs of faces): the final angle
    // optimization kept finding ever smaller gains there, for minutes
    {"OFF\n4 4 0\n0.97921306959170384 0.0022637550336435715 0.00049480968858131461\n"
     "-0.90216650990549885 0.018341724421612506 -0.0032352941176470589\n0.97921306959170384 0.0022637550336435715 0.50049480968858129\n"
     "-0.8998140548601129 0.018293897239287569 0.49676470588235294\n3 0 1 3\n3 0 3 2\n3 1 0 2\n3 1 2 3\n", 95, 147, 0, false},
  };
  for(const Case& c : cases) {
    Mesh in, out;
    std::istringstream is(c.off);
    REQUIRE(CGAL::IO::read_OFF(is, in));
    PR::Curvature_density density;
    density.smoothing = c.smoothing;
    const auto np = PR::parameters::target_vertex_count(c.target).random_seed(c.seed).number_of_iterations(3u);
    if(c.adaptive) REQUIRE_NOTHROW(PR::poisson_remesh(in, out, np.density(density)));
    else REQUIRE_NOTHROW(PR::poisson_remesh(in, out, np));
    CHECK(CGAL::is_valid_polygon_mesh(out));
    CHECK(CGAL::is_triangle_mesh(out));
    const long chi_in = long(num_vertices(in)) - long(num_edges(in)) + long(num_faces(in));
    CHECK(long(num_vertices(out)) - long(num_edges(out)) + long(num_faces(out)) == chi_in);
    CHECK(vertices_off_input(out, in) < 1e-9);
  }
}

TEST_CASE("an adaptive remesh follows the input more closely than a uniform one with as many vertices", "[remesh][adaptive]")
{
  // Issue 6: at the same vertex count, the curvature-adaptive remesh of smooth meshes is closer to
  // the input (Hausdorff distance) than the uniform one. The density is compared with the
  // remesher's fidelity insertions off in both runs (they mend the uniform remesh's worst rims
  // with a few pinned vertices) and the uniform runs without the feature grading (finer around
  // pointed tips, more vertices). One draw's Hausdorff distance rests on one rim (the uniform
  // dino's ratio goes from 0.45 to 0.77 over seeds 1-9), so the figures are medians over nine
  // seeds: the adaptive remesh at most 0.7 of the uniform distance, and still closer than the
  // uniform remesh with its fidelity insertions (the defaults).
  for(const std::string name : {"elephant", "dino"}) {
    SECTION(name) {
      Mesh in;
      PR::read_surface_mesh(test_support::data_mesh("meshes/" + name + ".off"), in);
      const std::size_t n = num_vertices(in);
      std::vector<double> ratios, adaptive_h, mended_h;
      for(unsigned int seed : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u}) {
        CAPTURE(seed);
        Mesh uniform, adaptive, mended;
        const auto np = PR::parameters::target_vertex_count(n).random_seed(seed);
        PR::poisson_remesh(in, uniform, np.fidelity_tolerance(0.0).feature_grading(false));
        const auto run = PR::poisson_remesh(in, adaptive, np.fidelity_tolerance(0.0).density(PR::Curvature_density()));
        PR::poisson_remesh(in, mended, np);
        const PR::Quality_report u = PR::quality_report(uniform, in), a = PR::quality_report(adaptive, in);
        CHECK(std::abs(double(a.number_of_vertices) - double(n)) < 0.05 * double(n));
        // (the uniform remesh's remakes may add a few more: more vertices only bring it closer)
        CHECK(double(u.number_of_vertices) > 0.95 * double(n));
        CHECK(double(u.number_of_vertices) < 1.08 * double(n));
        CHECK(run.sampling.max_radius > 2.5 * run.sampling.min_radius);   // really adaptive
        CHECK(a.euler_characteristic == u.euler_characteristic);
        CHECK(CGAL::is_closed(adaptive));
        CHECK(a.mean_min_angle > 51.5);
        CHECK(a.min_angle >= 25);
        CHECK(vertices_off_input(adaptive, in) < 1e-9);
        ratios.push_back(*a.hausdorff / *u.hausdorff);
        adaptive_h.push_back(*a.hausdorff);
        mended_h.push_back(*PR::quality_report(mended, in).hausdorff);
      }
      auto median = [](std::vector<double> v) { std::sort(v.begin(), v.end()); return v[v.size() / 2]; };
      CAPTURE(ratios);
      CHECK(median(ratios) < 0.7);
      CHECK(median(adaptive_h) < median(mended_h));
    }
  }
}

// ------------------------------------------------------------------ progress, cancellation, repair (issue 25)
TEST_CASE("a remesh reports its stages in order, a few hundred times at most, and stops when told", "[remesh][progress]")
{
  Mesh in, out;
  PR::read_surface_mesh(test_support::data_mesh("meshes/elephant.off"), in);
  std::vector<std::string> stages;
  std::size_t calls = 0, last_sampling = 0;
  bool sampling_grows = true;
  std::vector<double> fractions;
  const auto run = PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(800).random_seed(1u).regrading_attempts(0u)
    .progress([&](const PR::Progress& p) {
      ++calls;
      if(stages.empty() || stages.back() != p.stage) stages.push_back(p.stage);
      if(std::string(p.stage) == "sampling") {
        if(p.done < last_sampling) sampling_grows = false;
        last_sampling = p.done;
        CHECK(p.total > 0);
      }
      return true;
    })
    .callback([&](double f) { fractions.push_back(f); return true; }));
  CHECK(stages == std::vector<std::string>{"features", "sampling", "tessellation", "relaxation", "optimization"});
  CHECK(sampling_grows);
  // the reports are throttled to one per 1/200 of the expected count: the last one is within that
  // of the final count
  CHECK(last_sampling <= run.sampling.number_of_samples);
  CHECK(last_sampling + run.sampling.number_of_samples / 100 + 2 >= run.sampling.number_of_samples);
  CHECK(calls < 1500);
  REQUIRE(fractions.size() > 10);
  CHECK(fractions.front() >= 0);
  CHECK(fractions.back() == Approx(1.0));
  CHECK(std::is_sorted(fractions.begin(), fractions.end()));

  // the same run without reports gives the same mesh (reporting changes nothing)
  Mesh plain;
  PR::poisson_remesh(in, plain, PR::parameters::target_vertex_count(800).random_seed(1u).regrading_attempts(0u));
  CHECK(num_vertices(plain) == num_vertices(out));
  bool same = true;
  for(auto v : vertices(plain)) same = same && plain.point(v) == out.point(v);
  CHECK(same);

  // false stops the run with Cancelled, in the stage that said so
  Mesh stopped;
  try {
    PR::poisson_remesh(in, stopped, PR::parameters::target_vertex_count(800).progress([](const PR::Progress& p) {
      return !(std::string(p.stage) == "sampling" && p.done > 100); }));
    FAIL("not cancelled");
  } catch(const PR::Cancelled& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains("sampling"));
  }
  // and so does CGAL's callback, here in the relaxation (past 40% of the run)
  CHECK_THROWS_AS(PR::poisson_remesh(in, stopped, PR::parameters::target_vertex_count(800).callback([](double f) { return f < 0.5; })),
                  PR::Cancelled);
  // the sampler alone reports too
  std::vector<PR::Poisson_sample<Mesh, Point>> samples;
  std::size_t sampler_calls = 0;
  PR::poisson_disk_sample(in, std::back_inserter(samples), PR::parameters::target_vertex_count(500)
    .progress([&](const PR::Progress&) { ++sampler_calls; return true; }));
  CHECK(sampler_calls > 2);
  CHECK(sampler_calls < 600);
}

TEST_CASE("poisson_remesh removes the zero-area faces of its input first, unless strict", "[remesh][repair]")
{
  // a tetrahedron whose edge A-B is split at M on one side only, closed by the zero-area face A-M-B
  Mesh in, out;
  const auto a = in.add_vertex(Point(0, 0, 0)), b = in.add_vertex(Point(1, 0, 0)), c = in.add_vertex(Point(0, 1, 0)),
             d = in.add_vertex(Point(0, 0, 1)), m = in.add_vertex(Point(0.5, 0, 0));
  for(auto f : {std::array<Mesh::Vertex_index, 3>{{a, c, m}}, {{m, c, b}}, {{a, b, d}}, {{a, d, c}}, {{b, c, d}}, {{a, m, b}}})
    REQUIRE(in.add_face(f[0], f[1], f[2]) != Mesh::null_face());
  REQUIRE(CGAL::is_closed(in));
  const auto run = PR::poisson_remesh(in, out, PR::parameters::target_vertex_count(80).random_seed(2u));
  CHECK(run.number_of_repaired_faces == 1);
  CHECK(num_vertices(in) == 5);   // the caller's input is untouched
  const PR::Quality_report q = PR::quality_report(out, in);
  CHECK(q.number_of_degenerate_faces == 0);
  CHECK(q.number_of_border_edges == 0);
  CHECK(q.genus == 0);
  CHECK(q.number_of_components == 1);
  CHECK(q.min_angle > 20);
  CHECK(vertices_off_input(out, in) < 1e-9);
  Mesh refused;
  CHECK_THROWS_AS(PR::poisson_remesh(in, refused, PR::parameters::target_vertex_count(80).strict_input(true)), std::invalid_argument);
}

TEST_CASE("a local remake draws the region around a place anew, finer, leaves the rest as it was, and is taken back", "[remesh][local_remake]")
{
  // the input, and the output before the remake: a unit square of 40 x 40 split squares; the
  // output's border vertices are feature samples (the corners corners), the others surface samples
  const Mesh in = analytic::plane(40, 40).to_mesh<Mesh>();
  const auto features = PR::detect_features(in);
  Mesh out = in;
  auto kind = get(CGAL::dynamic_vertex_property_t<int>(), out);
  std::size_t border_vertices = 0;
  for(auto v : vertices(out)) {
    int degree_on_border = 0;
    for(auto h : CGAL::halfedges_around_target(v, out)) if(is_border(edge(h, out), out)) ++degree_on_border;
    const bool corner = degree_on_border > 0 && degree(v, out) == 2;
    put(kind, v, int(corner ? PR::Sample_kind::corner : degree_on_border > 0 ? PR::Sample_kind::feature : PR::Sample_kind::surface));
    if(degree_on_border > 0) ++border_vertices;
  }
  auto is_feature = [&](boost::graph_traits<Mesh>::edge_descriptor e) { return is_border(e, out); };
  auto is_tip = [](boost::graph_traits<Mesh>::vertex_descriptor) { return false; };
  const double r = 0.0125;   // (the spacing 2r: the grid's)
  const Point place(0.5, 0.5, 0);
  std::vector<double> radii;
  PR::internal::regrade_radii(in, get(CGAL::vertex_point, in), r, std::vector<Point>{place}, radii);
  PR::Lloyd_relaxer<Mesh, K> relaxer(in, features);
  const PR::Exact_geodesic_oracle<Mesh, boost::property_map<Mesh, CGAL::vertex_point_t>::const_type> oracle(in, get(CGAL::vertex_point, in));
  const PR::internal::Local_remake_settings settings;
  PR::internal::Local_remake_statistics stats;
  PR::internal::Local_remake_undo<Mesh> undo;
  auto near = [&](const Mesh& m, double d) {
    std::size_t n = 0;
    for(auto v : vertices(m)) if(CGAL::squared_distance(m.point(v), place) < d * d) ++n;
    return n;
  };
  const std::size_t near_before = near(out, 2 * r);
  REQUIRE(PR::internal::remake_regions(in, get(CGAL::vertex_point, in), oracle, relaxer, PR::Relaxation_settings(), out, kind, is_feature, is_tip,
                                       std::vector<Point>{place}, r, radii, 7u, settings, stats, undo));
  CHECK(stats.region_vertices > 0);
  CHECK(stats.new_samples > 0);
  // finer around the place (radii a quarter of r there: about 16 times the density)
  CHECK(near(out, 2 * r) >= 4 * near_before);
  // beyond the patch (the region's reach and an edge), the very same vertices
  const double beyond = (settings.region_reach + 3) * r;
  std::vector<Point> far_in, far_out;
  for(auto v : vertices(in)) if(CGAL::squared_distance(in.point(v), place) > beyond * beyond) far_in.push_back(in.point(v));
  for(auto v : vertices(out)) if(!out.is_removed(v) && CGAL::squared_distance(out.point(v), place) > beyond * beyond) far_out.push_back(out.point(v));
  std::sort(far_in.begin(), far_in.end());
  std::sort(far_out.begin(), far_out.end());
  CHECK(far_in == far_out);
  // a valid disk with the same border, every new triangle shaped, nothing off the plane
  Mesh check = out;
  check.collect_garbage();
  CHECK(CGAL::is_valid_polygon_mesh(check));
  CHECK(long(num_vertices(check)) - long(num_edges(check)) + long(num_faces(check)) == 1);
  std::size_t border_after = 0;
  for(auto h : halfedges(check)) if(is_border(h, check)) ++border_after;
  CHECK(border_after == border_vertices);
  double smallest = 180;
  for(auto f : faces(check)) {
    const auto h = halfedge(f, check);
    const Point p[3] = {check.point(source(h, check)), check.point(target(h, check)), check.point(target(next(h, check), check))};
    for(int k = 0; k < 3; ++k) smallest = std::min(smallest, CGAL::to_double(CGAL::approximate_angle(p[(k + 1) % 3], p[k], p[(k + 2) % 3])));
  }
  CHECK(smallest > 20);
  for(auto v : vertices(check)) CHECK(std::abs(check.point(v).z()) < 1e-12);
  // taken back: the output before the remake, vertex for vertex
  PR::internal::undo_remake(out, kind, undo);
  out.collect_garbage();
  std::vector<Point> all_in, all_out;
  for(auto v : vertices(in)) all_in.push_back(in.point(v));
  for(auto v : vertices(out)) all_out.push_back(out.point(v));
  std::sort(all_in.begin(), all_in.end());
  std::sort(all_out.begin(), all_out.end());
  CHECK(all_in == all_out);
  CHECK(num_faces(out) == num_faces(in));
}
