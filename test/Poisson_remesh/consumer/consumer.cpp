// Uses the installed headers: a regular tetrahedron has 60 degree angles and genus 0.
#include <Poisson_remesh/quality_report.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <cmath>
#include <iostream>

int main()
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  CGAL::Surface_mesh<K::Point_3> m;
  CGAL::make_tetrahedron(K::Point_3(1, 1, 1), K::Point_3(1, -1, -1), K::Point_3(-1, 1, -1), K::Point_3(-1, -1, 1), m);
  const Poisson_remesh::Quality_report r = Poisson_remesh::quality_report(m);
  const bool ok = std::abs(r.min_angle - 60) < 1e-9 && std::abs(r.max_angle - 60) < 1e-9 && r.genus == 0 &&
                  r.number_of_components == 1;
  std::cout << "consumer: min angle " << r.min_angle << ", genus " << r.genus << (ok ? " ok" : " WRONG") << "\n";
  return ok ? 0 : 1;
}
