// Poisson_remesh/IO/write_density_map_svg.h
//
// Entry point: write_density_map_svg(os, mesh, value_of_vertex, np) -- a picture of a scalar field
// on a triangle mesh (the sampling density of Fig. 6, a disk radius, a curvature): the mesh seen
// along an axis (orthographic, painter's algorithm), each face filled with the colour of the mean
// of its vertex values on a logarithmic blue (low) to red (high) scale (2% to 98% quantiles), darkened by the angle to
// the viewer; a colour bar gives the range. Self-contained SVG 1.1, no script.

#ifndef POISSON_REMESH_IO_WRITE_DENSITY_MAP_SVG_H
#define POISSON_REMESH_IO_WRITE_DENSITY_MAP_SVG_H

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Kernel_traits.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

namespace Poisson_remesh {

/// How write_density_map_svg() looks at the mesh.
struct Density_map_view
{
  /// the viewing direction (the viewer looks along it); 0 = -z, 1 = -y, 2 = -x, 3 = +z, 4 = +y,
  /// 5 = +x; -1 (the default): along the smallest extent of the bounding box, so that the widest
  /// side shows
  int axis = -1;
  double width = 640;          ///< picture width in pixels (the height follows the mesh)
  std::string title;           ///< printed at the top
  std::string value_name = "density";   ///< the name of the value, in the colour scale's legend
};

namespace internal {

// blue - cyan - yellow - red
inline std::array<double, 3> heat_color(double t)
{
  t = std::min(1.0, std::max(0.0, t));
  const double stops[4][3] = {{0.15, 0.25, 0.85}, {0.2, 0.8, 0.85}, {0.95, 0.85, 0.2}, {0.85, 0.15, 0.1}};
  const double x = 3 * t;
  const int i = std::min(2, int(x));
  const double u = x - i;
  return {{stops[i][0] + u * (stops[i + 1][0] - stops[i][0]), stops[i][1] + u * (stops[i + 1][1] - stops[i][1]),
           stops[i][2] + u * (stops[i + 1][2] - stops[i][2])}};
}

inline std::string svg_rgb(const std::array<double, 3>& c, double shade)
{
  char b[32];
  std::snprintf(b, sizeof(b), "#%02x%02x%02x", int(255 * c[0] * shade), int(255 * c[1] * shade), int(255 * c[2] * shade));
  return b;
}

/// `axis` (0..5, see Density_map_view) or, when it is negative, the view along the smallest
/// extent of `tm`'s bounding box (0, 1 or 2), so that the widest side shows
template <class TriangleMesh>
int viewing_axis(const TriangleMesh& tm, int axis)
{
  if(axis >= 0) return axis;
  auto vpm = get(CGAL::vertex_point, tm);
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for(auto v : vertices(tm)) {
    const auto& p = get(vpm, v);
    const double c[3] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    for(int i = 0; i < 3; ++i) { lo[i] = std::min(lo[i], c[i]); hi[i] = std::max(hi[i], c[i]); }
  }
  const double ext[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  return ext[2] <= ext[0] && ext[2] <= ext[1] ? 0 : (ext[1] <= ext[0] ? 1 : 2);
}

} // namespace internal

/*!
  writes `tm` coloured by `value(v)` (> 0 at each vertex; any callable on vertex descriptors) as
  an SVG picture to `os`. Faces turned away from the viewer are drawn too (darker), so open and
  thin parts stay visible.
*/
template <class TriangleMesh, class VertexValue>
void write_density_map_svg(std::ostream& os, const TriangleMesh& tm, VertexValue value, const Density_map_view& view = {})
{
  typedef typename boost::property_traits<typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::const_type>::value_type Point_3;
  auto vpm = get(CGAL::vertex_point, tm);
  const int axis = internal::viewing_axis(tm, view.axis);
  const int a = axis % 3, sign = axis < 3 ? -1 : 1;
  // screen axes (u right, v up) and depth w towards the viewer
  const int ui = a == 0 ? 0 : (a == 1 ? 0 : 1), vi = a == 0 ? 1 : (a == 1 ? 2 : 2);
  auto coord = [](const Point_3& p, int i) { return CGAL::to_double(i == 0 ? p.x() : (i == 1 ? p.y() : p.z())); };
  const int wi = 3 - ui - vi;
  double lo = HUGE_VAL, hi = -HUGE_VAL, umin = HUGE_VAL, umax = -HUGE_VAL, vmin = HUGE_VAL, vmax = -HUGE_VAL;
  std::vector<double> values;
  for(auto v : vertices(tm)) {
    const double x = value(v);
    if(x > 0) values.push_back(x);
    const Point_3& p = get(vpm, v);
    umin = std::min(umin, coord(p, ui)); umax = std::max(umax, coord(p, ui));
    vmin = std::min(vmin, coord(p, vi)); vmax = std::max(vmax, coord(p, vi));
  }
  // the colour range: from the 2% to the 98% quantile (a few extreme vertices would wash out
  // the picture); values beyond take the end colours
  if(values.empty()) { lo = hi = 1; }
  else {
    std::sort(values.begin(), values.end());
    lo = values[std::size_t(0.02 * double(values.size() - 1))];
    hi = values[std::size_t(0.98 * double(values.size() - 1))];
  }
  const double margin = 40, bar = 60;
  const double scale = (view.width - 2 * margin - bar) / std::max(umax - umin, 1e-300);
  const double height = (vmax - vmin) * scale + 2 * margin + 20;
  // the u axis flips with the viewing side so that the picture is never mirrored
  const double flip = (sign > 0) == (a != 1) ? 1 : -1;
  struct Tri { double depth; std::array<double, 6> xy; std::string fill; };
  std::vector<Tri> tris;
  for(auto f : faces(tm)) {
    const auto h = halfedge(f, tm);
    const Point_3 p[3] = {get(vpm, source(h, tm)), get(vpm, target(h, tm)), get(vpm, target(next(h, tm), tm))};
    double mean = 0;
    for(auto v : {source(h, tm), target(h, tm), target(next(h, tm), tm)}) mean += value(v) / 3;
    const double t = hi > lo ? std::log(std::min(hi, std::max(mean, lo)) / lo) / std::log(hi / lo) : 0.5;
    double n[3] = {0, 0, 0};
    const double e1[3] = {coord(p[1], 0) - coord(p[0], 0), coord(p[1], 1) - coord(p[0], 1), coord(p[1], 2) - coord(p[0], 2)};
    const double e2[3] = {coord(p[2], 0) - coord(p[0], 0), coord(p[2], 1) - coord(p[0], 1), coord(p[2], 2) - coord(p[0], 2)};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1]; n[1] = e1[2] * e2[0] - e1[0] * e2[2]; n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double facing = nn > 0 ? -sign * n[a] / nn : 0;   // > 0: towards the viewer
    const double shade = facing > 0 ? 0.45 + 0.55 * facing : 0.3;
    Tri tri;
    tri.depth = 0;
    for(int k = 0; k < 3; ++k) {
      tri.depth += -sign * coord(p[k], wi) / 3;
      tri.xy[2 * k] = margin + scale * (flip > 0 ? coord(p[k], ui) - umin : umax - coord(p[k], ui));
      tri.xy[2 * k + 1] = margin + 20 + scale * (vmax - coord(p[k], vi));
    }
    tri.fill = internal::svg_rgb(internal::heat_color(t), shade);
    tris.push_back(tri);
  }
  // farthest first
  std::sort(tris.begin(), tris.end(), [](const Tri& x, const Tri& y) { return x.depth < y.depth; });
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << view.width << "\" height=\"" << height
     << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if(!view.title.empty()) os << "<text x=\"" << margin << "\" y=\"20\" font-size=\"14\">" << view.title << "</text>\n";
  char b[160];
  for(const Tri& t : tris) {
    std::snprintf(b, sizeof(b), "<path d=\"M%.1f %.1fL%.1f %.1fL%.1f %.1fZ\" fill=\"%s\" stroke=\"%s\" stroke-width=\"0.2\"/>\n",
                  t.xy[0], t.xy[1], t.xy[2], t.xy[3], t.xy[4], t.xy[5], t.fill.c_str(), t.fill.c_str());
    os << b;
  }
  // colour bar, low at the bottom
  const double bx = view.width - bar + 5, by = margin + 20, bh = std::max(100.0, height - 2 * margin - 40);
  for(int i = 0; i < 20; ++i) {
    std::snprintf(b, sizeof(b), "<rect x=\"%.1f\" y=\"%.1f\" width=\"14\" height=\"%.1f\" fill=\"%s\"/>\n", bx,
                  by + bh * i / 20.0, bh / 20.0 + 0.5, internal::svg_rgb(internal::heat_color(1 - (i + 0.5) / 20.0), 1.0).c_str());
    os << b;
  }
  std::snprintf(b, sizeof(b), "<text x=\"%.1f\" y=\"%.1f\">%.3g</text>\n<text x=\"%.1f\" y=\"%.1f\">%.3g</text>\n", bx - 10, by - 4, hi,
                bx - 10, by + bh + 14, lo);
  os << b << "<text x=\"" << bx - 10 << "\" y=\"" << by + bh + 28 << "\">" << view.value_name << "</text>\n</svg>\n";
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_IO_WRITE_DENSITY_MAP_SVG_H
