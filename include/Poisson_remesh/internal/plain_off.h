// Poisson_remesh/internal/plain_off.h
//
// Reading and writing the plain ASCII form of OFF (the "OFF" keyword, the counts, one vertex of
// three coordinates per line, one face of n indices per line) without iostreams.
//
// Why not CGAL's: its OFF reader makes an istringstream per line and reads each number through
// the stream's locale, and its writer formats through the stream: a large part of the program's
// own time around the remesh (RESULTS, "The program around the remesh"). Here numbers are read
// with std::from_chars (correctly rounded, as glibc's strtod behind the stream) and written with
// std::to_chars (the shortest digits that read back to the same double), so a file written here
// reads back to the same points and faces.
//
// The reader takes only files it reads unambiguously. Anything else makes it return false and
// leave the caller to CGAL's reader, whose results and error messages then apply unchanged:
// another keyword than OFF or COFF (NOFF, 4OFF, binary...), more than three numbers on a vertex
// line (besides COFF's colour of three or four), more than n indices on a face line (a face
// colour), a sign '+', a non-finite or out-of-range number, an index past the vertices, a face of
// fewer than three vertices, no vertex or no face, text after the last face. '#' comments and
// blank lines are skipped wherever CGAL's reader skips them.

#ifndef POISSON_REMESH_INTERNAL_PLAIN_OFF_H
#define POISSON_REMESH_INTERNAL_PLAIN_OFF_H

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <ostream>
#include <string>
#include <system_error>
#include <vector>

namespace Poisson_remesh {
namespace internal {

namespace plain_off_detail {

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// skips blanks, line ends and '#' comments up to the next token
inline const char* skip_to_token(const char* p, const char* e)
{
  while(p < e) {
    if(is_blank(*p) || *p == '\n') ++p;
    else if(*p == '#') { while(p < e && *p != '\n') ++p; }
    else break;
  }
  return p;
}

// skips the blanks between two numbers of the same line; false when there are none
inline bool skip_separator(const char*& p, const char* e)
{
  const char* q = p;
  while(p < e && (*p == ' ' || *p == '\t')) ++p;
  return p != q;
}

// true when only blanks and a comment remain on the line (p is then past its end)
inline bool end_of_line(const char*& p, const char* e)
{
  while(p < e && is_blank(*p)) ++p;
  if(p < e && *p == '#') while(p < e && *p != '\n') ++p;
  if(p == e) return true;
  if(*p != '\n') return false;
  ++p;
  return true;
}

template <class T>
bool number(const char*& p, const char* e, T& value)
{
  const std::from_chars_result r = std::from_chars(p, e, value);
  if(r.ec != std::errc() || r.ptr == p) return false;
  p = r.ptr;
  return true;
}

} // namespace plain_off_detail

/// Reads `fname` into `points` and `polygons` when it is a plain ASCII OFF file (see the file
/// comment); returns false, with both empty, for anything else.
template <class Point>
bool read_plain_off(const std::string& fname, std::vector<Point>& points, std::vector<std::vector<std::size_t>>& polygons)
{
  using namespace plain_off_detail;
  points.clear();
  polygons.clear();
  std::string text;
  {
    std::ifstream in(fname, std::ios::binary);
    if(!in) return false;
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if(size <= 0) return false;
    text.resize(std::size_t(size));
    in.seekg(0);
    if(!in.read(&text[0], size)) return false;
  }
  const char* p = text.data();
  const char* const e = p + text.size();
  auto fail = [&] { points.clear(); polygons.clear(); return false; };

  p = skip_to_token(p, e);
  // ("COFF": each vertex line ends with a colour of three or four numbers, which are not kept)
  const bool colours = e - p >= 1 && p[0] == 'C';
  if(colours) ++p;
  if(e - p < 4 || p[0] != 'O' || p[1] != 'F' || p[2] != 'F' || !(is_blank(p[3]) || p[3] == '\n')) return false;
  p += 3;
  std::size_t counts[3];
  for(std::size_t& c : counts) {
    p = skip_to_token(p, e);
    if(!number(p, e, c)) return fail();
  }
  if(!end_of_line(p, e)) return fail();
  const std::size_t nv = counts[0], nf = counts[1];
  // (each vertex and face takes more than one byte: larger counts are a malformed file's)
  if(nv == 0 || nf == 0 || nv > text.size() || nf > text.size()) return fail();
  points.reserve(nv);
  for(std::size_t i = 0; i < nv; ++i) {
    double c[3];
    p = skip_to_token(p, e);
    for(int k = 0; k < 3; ++k)
      if((k > 0 && !skip_separator(p, e)) || !number(p, e, c[k]) || !std::isfinite(c[k])) return fail();
    if(colours) {
      int n = 0;
      for(double component; n < 4 && skip_separator(p, e) && p < e && *p != '#' && *p != '\n' && *p != '\r'; ++n)
        if(!number(p, e, component) || !std::isfinite(component)) return fail();
      if(n < 3) return fail();
    }
    if(!end_of_line(p, e)) return fail();
    points.emplace_back(c[0], c[1], c[2]);
  }
  polygons.resize(nf);
  for(std::size_t f = 0; f < nf; ++f) {
    std::size_t n = 0;
    p = skip_to_token(p, e);
    if(!number(p, e, n) || n < 3 || n > nv) return fail();
    std::vector<std::size_t>& poly = polygons[f];
    poly.resize(n);
    for(std::size_t& v : poly)
      if(!skip_separator(p, e) || !number(p, e, v) || v >= nv) return fail();
    if(!end_of_line(p, e)) return fail();
  }
  if(skip_to_token(p, e) != e) return fail();
  return true;
}

/// Writes points and polygons (index lists) as plain ASCII OFF, the coordinates in their shortest
/// exact digits.
inline void write_plain_off(std::ostream& os, const std::vector<std::array<double, 3>>& points,
                            const std::vector<std::vector<std::size_t>>& polygons)
{
  std::string buffer;
  char digits[64];
  auto put = [&](auto value) {
    const std::to_chars_result r = std::to_chars(digits, digits + sizeof(digits), value);
    buffer.append(digits, r.ptr);
  };
  auto flush_if_full = [&] {
    if(buffer.size() > (std::size_t(1) << 16)) { os.write(buffer.data(), std::streamsize(buffer.size())); buffer.clear(); }
  };
  buffer += "OFF\n";
  put(points.size());
  buffer += ' ';
  put(polygons.size());
  buffer += " 0\n";
  for(const std::array<double, 3>& q : points) {
    put(q[0]); buffer += ' ';
    put(q[1]); buffer += ' ';
    put(q[2]); buffer += '\n';
    flush_if_full();
  }
  for(const std::vector<std::size_t>& poly : polygons) {
    put(poly.size());
    for(std::size_t v : poly) { buffer += ' '; put(v); }
    buffer += '\n';
    flush_if_full();
  }
  os.write(buffer.data(), std::streamsize(buffer.size()));
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_PLAIN_OFF_H
