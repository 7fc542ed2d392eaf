// Poisson_remesh/internal/xml_escape.h
//
// Text for XML and SVG documents (quality reports, pictures): the characters with a meaning in
// markup replaced by their entities.

#ifndef POISSON_REMESH_INTERNAL_XML_ESCAPE_H
#define POISSON_REMESH_INTERNAL_XML_ESCAPE_H

#include <string>

namespace Poisson_remesh {
namespace internal {

inline std::string xml_escape(const std::string& s)
{
  std::string out;
  for(char c : s) {
    switch(c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

} // namespace internal
} // namespace Poisson_remesh

#endif // POISSON_REMESH_INTERNAL_XML_ESCAPE_H
