// Poisson_remesh/IO/write_mesh_svg.h
//
// Entry points:
//   write_mesh_svg(os, mesh, view)                 -- a picture of one triangle mesh;
//   write_mesh_comparison_svg(os, meshes, view)    -- several meshes side by side, seen from the
//                                                     same direction at the same scale.
// (The angle histograms are write_angle_histogram_svg() of IO/write_quality_report.h.)
// The pictures a user judges a remesher by: flat-shaded faces with their edges drawn, and the
// triangles whose smallest angle is under a threshold (30 degrees by default) filled red, so that
// the bad triangles are seen at once. Orthographic projection, painter's algorithm (farthest face
// first), self-contained SVG 1.1 with no script and no dependency.

#ifndef POISSON_REMESH_IO_WRITE_MESH_SVG_H
#define POISSON_REMESH_IO_WRITE_MESH_SVG_H

#include <Poisson_remesh/IO/write_density_map_svg.h>
#include <Poisson_remesh/internal/xml_escape.h>

#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace Poisson_remesh {

/// How write_mesh_svg() and write_mesh_comparison_svg() look at the meshes.
struct Mesh_svg_view
{
  /// The base direction, as in write_density_map_svg(): 0 = -z, 1 = -y, 2 = -x, 3 = +z, 4 = +y,
  /// 5 = +x; -1 (the default): along the smallest extent of the bounding box of the first mesh.
  int axis = -1;
  double yaw_degrees = 25;     ///< the view turned about the picture's vertical axis
  double pitch_degrees = 20;   ///< and then about its horizontal axis (a three-quarter view)
  double width = 640;          ///< width of one mesh's panel in pixels (the height follows)
  std::string title;           ///< printed at the top of the picture
  bool wireframe = true;       ///< draw the edges
  /// Faces whose smallest angle is below this (degrees) are filled red; 0 marks none.
  double marked_angle_degrees = 30;
};

namespace internal {

typedef std::array<double, 3> Svg_vec;

inline Svg_vec svg_sub(const Svg_vec& a, const Svg_vec& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
inline double svg_dot(const Svg_vec& a, const Svg_vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Svg_vec svg_cross(const Svg_vec& a, const Svg_vec& b)
{
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
inline Svg_vec svg_comb(double s, const Svg_vec& a, double t, const Svg_vec& b)
{
  return {{s * a[0] + t * b[0], s * a[1] + t * b[1], s * a[2] + t * b[2]}};
}

/// The smallest angle of the triangle (p, q, r), in degrees (0 where degenerate).
inline double svg_smallest_angle_degrees(const Svg_vec& p, const Svg_vec& q, const Svg_vec& r)
{
  const Svg_vec P[3] = {p, q, r};
  double best = 180;
  for(int i = 0; i < 3; ++i) {
    const Svg_vec a = svg_sub(P[(i + 1) % 3], P[i]), b = svg_sub(P[(i + 2) % 3], P[i]), x = svg_cross(a, b);
    best = std::min(best, std::atan2(std::sqrt(svg_dot(x, x)), svg_dot(a, b)) * 57.29577951308232);
  }
  return best;
}

/// The screen frame of a view: u right, v up, w towards the viewer.
struct Svg_camera
{
  Svg_vec u, v, w;
};

template <class TriangleMesh>
Svg_camera svg_camera(const TriangleMesh& tm, const Mesh_svg_view& view)
{
  const int axis = viewing_axis(tm, view.axis);
  const int a = axis % 3;
  const double sign = axis < 3 ? 1 : -1;   // the viewer on the + side of axis a for 0..2
  Svg_vec e[3] = {{{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}};
  // base frame: w0 towards the viewer, v0 up, u0 = v0 x w0 (right-handed, never mirrored)
  const int wi = 2 - a, vi = wi == 2 ? 1 : 2;
  Svg_camera c;
  const Svg_vec w0 = svg_comb(sign, e[wi], 0, e[wi]), v0 = e[vi], u0 = svg_cross(v0, w0);
  const double y = view.yaw_degrees / 57.29577951308232, p = view.pitch_degrees / 57.29577951308232;
  // yaw about v0, then pitch about the new u
  const Svg_vec u1 = svg_comb(std::cos(y), u0, -std::sin(y), w0), w1 = svg_comb(std::sin(y), u0, std::cos(y), w0);
  c.u = u1;
  c.v = svg_comb(std::cos(p), v0, -std::sin(p), w1);
  c.w = svg_comb(std::sin(p), v0, std::cos(p), w1);
  return c;
}

/// One face as drawn.
struct Svg_face
{
  double depth;
  std::array<double, 6> xy;
  bool front, marked;
  double facing;   // the unit normal's component towards the viewer
  double lambert;  // |cosine| of the angle to the light
  double shade;
};

template <class TriangleMesh>
std::vector<Svg_face> svg_faces(const TriangleMesh& tm, const Svg_camera& cam, const Mesh_svg_view& view)
{
  auto vpm = get(CGAL::vertex_point, tm);
  auto coords = [&](typename boost::graph_traits<TriangleMesh>::vertex_descriptor v) {
    const auto& p = get(vpm, v);
    return Svg_vec{{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
  };
  // light from the upper left, slightly in front
  Svg_vec light = svg_comb(1, svg_comb(0.9, cam.w, 0.5, cam.v), -0.35, cam.u);
  const double ll = std::sqrt(svg_dot(light, light));
  for(double& x : light) x /= ll;
  std::vector<Svg_face> out;
  out.reserve(num_faces(tm));
  for(auto f : faces(tm)) {
    const auto h = halfedge(f, tm);
    const Svg_vec p[3] = {coords(source(h, tm)), coords(target(h, tm)), coords(target(next(h, tm), tm))};
    Svg_vec n = svg_cross(svg_sub(p[1], p[0]), svg_sub(p[2], p[0]));
    const double nn = std::sqrt(svg_dot(n, n));
    if(nn > 0) for(double& x : n) x /= nn;
    Svg_face face;
    face.depth = 0;
    for(int k = 0; k < 3; ++k) {
      face.depth += svg_dot(p[k], cam.w) / 3;
      face.xy[2 * k] = svg_dot(p[k], cam.u);
      face.xy[2 * k + 1] = svg_dot(p[k], cam.v);
    }
    face.facing = svg_dot(n, cam.w);
    face.lambert = std::abs(svg_dot(n, light));
    face.marked = view.marked_angle_degrees > 0 && svg_smallest_angle_degrees(p[0], p[1], p[2]) < view.marked_angle_degrees;
    out.push_back(face);
  }
  std::sort(out.begin(), out.end(), [](const Svg_face& a, const Svg_face& b) { return a.depth < b.depth; });
  // The side seen first is the front: the nearest faces (the last 1% drawn) decide, so that a
  // mesh oriented inwards still shows grey, and only the far side of an open mesh seen through a
  // hole shows blue-grey
  double near_facing = 0;
  for(std::size_t i = out.size() - std::min(out.size(), std::max<std::size_t>(1, out.size() / 100)); i < out.size(); ++i)
    near_facing += out[i].facing;
  const double side = near_facing < 0 ? -1 : 1;
  for(Svg_face& face : out) {
    face.front = side * face.facing >= 0;
    face.shade = face.front ? 0.35 + 0.65 * face.lambert : 0.3 + 0.3 * face.lambert;
  }
  return out;
}

inline std::string svg_grey_or_red(bool marked, bool front, double shade)
{
  // front faces light grey, back faces (open meshes) blue-grey, marked faces red
  const double base[3][3] = {{0.86, 0.86, 0.84}, {0.55, 0.6, 0.75}, {0.92, 0.16, 0.12}};
  const double* c = marked ? base[2] : (front ? base[0] : base[1]);
  char b[16];
  std::snprintf(b, sizeof(b), "#%02x%02x%02x", int(255 * std::min(1.0, c[0] * shade)), int(255 * std::min(1.0, c[1] * shade)),
                int(255 * std::min(1.0, c[2] * shade)));
  return b;
}

} // namespace internal

/*!
  writes the meshes of `meshes` (pairs of a pointer to a triangle mesh and a caption) side by side
  as one SVG picture to `os`: the same viewing direction (chosen on the first mesh, see
  `Mesh_svg_view`) and the same scale for all, flat-shaded, the edges drawn, and each triangle
  whose smallest angle is under `view.marked_angle_degrees` filled red; each caption is followed
  by the number of faces and of red faces. Each face is one `<path>` element, in back-to-front
  order; a red face's fill starts with the class attribute `class="marked"`.
*/
template <class TriangleMesh>
void write_mesh_comparison_svg(std::ostream& os, const std::vector<std::pair<const TriangleMesh*, std::string>>& meshes,
                               const Mesh_svg_view& view = {})
{
  if(meshes.empty()) return;
  const internal::Svg_camera cam = internal::svg_camera(*meshes.front().first, view);
  std::vector<std::vector<internal::Svg_face>> drawn;
  std::vector<std::array<double, 2>> offset;   // each panel's own left and top (umin, vmax)
  double widest = 0, tallest = 0;              // one scale for all: the widest panel fills its width
  for(const auto& m : meshes) {
    drawn.push_back(internal::svg_faces(*m.first, cam, view));
    double pu0 = HUGE_VAL, pu1 = -HUGE_VAL, pv0 = HUGE_VAL, pv1 = -HUGE_VAL;
    for(const auto& f : drawn.back())
      for(int k = 0; k < 3; ++k) {
        pu0 = std::min(pu0, f.xy[2 * k]); pu1 = std::max(pu1, f.xy[2 * k]);
        pv0 = std::min(pv0, f.xy[2 * k + 1]); pv1 = std::max(pv1, f.xy[2 * k + 1]);
      }
    offset.push_back({{pu0, pv1}});
    widest = std::max(widest, pu1 - pu0);
    tallest = std::max(tallest, pv1 - pv0);
  }
  const double margin = 20, top = view.title.empty() ? 24 : 44, bottom = 24;
  const double scale = (view.width - 2 * margin) / std::max(widest, 1e-300);
  const double height = top + tallest * scale + bottom + margin;
  const double total_width = view.width * double(meshes.size());
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << total_width << "\" height=\"" << height
     << "\" font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if(!view.title.empty()) os << "<text x=\"" << margin << "\" y=\"22\" font-size=\"15\">" << internal::xml_escape(view.title) << "</text>\n";
  char b[256];
  for(std::size_t i = 0; i < drawn.size(); ++i) {
    const double x0 = view.width * double(i) + margin, y0 = top;
    // stroke width from the mean projected edge length, so that dense meshes do not turn black
    double mean_edge = 0;
    for(const auto& f : drawn[i]) mean_edge += std::hypot(f.xy[2] - f.xy[0], f.xy[3] - f.xy[1]) * scale;
    mean_edge /= std::max<std::size_t>(1, drawn[i].size());
    const double stroke = std::min(0.6, std::max(0.08, 0.06 * mean_edge));
    std::size_t marked = 0;
    for(const auto& f : drawn[i]) {
      const std::string fill = internal::svg_grey_or_red(f.marked, f.front, f.shade);
      marked += f.marked;
      double xy[6];
      for(int k = 0; k < 3; ++k) {
        xy[2 * k] = x0 + scale * (f.xy[2 * k] - offset[i][0]);
        xy[2 * k + 1] = y0 + scale * (offset[i][1] - f.xy[2 * k + 1]);
      }
      std::snprintf(b, sizeof(b), "<path %sd=\"M%.2f %.2fL%.2f %.2fL%.2f %.2fZ\" fill=\"%s\" stroke=\"%s\" stroke-width=\"%.2f\" stroke-linejoin=\"round\"/>\n",
                    f.marked ? "class=\"marked\" " : "", xy[0], xy[1], xy[2], xy[3], xy[4], xy[5], fill.c_str(),
                    view.wireframe ? "#303030" : fill.c_str(), view.wireframe ? stroke : 0.2);
      os << b;
    }
    std::snprintf(b, sizeof(b), " (%zu faces, %zu under %g&#176;)", drawn[i].size(), marked, view.marked_angle_degrees);
    os << "<text x=\"" << x0 << "\" y=\"" << height - margin << "\">" << internal::xml_escape(meshes[i].second)
       << (view.marked_angle_degrees > 0 ? std::string(b) : std::string()) << "</text>\n";
  }
  os << "</svg>\n";
}

/// writes one mesh as write_mesh_comparison_svg() does, with `caption` under it
template <class TriangleMesh>
void write_mesh_svg(std::ostream& os, const TriangleMesh& tm, const Mesh_svg_view& view = {}, const std::string& caption = "")
{
  write_mesh_comparison_svg<TriangleMesh>(os, {{&tm, caption}}, view);
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_IO_WRITE_MESH_SVG_H
