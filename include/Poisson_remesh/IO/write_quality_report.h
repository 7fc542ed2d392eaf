// Poisson_remesh/IO/write_quality_report.h
//
// Presents Quality_report values: a human table (one column per mesh, so "before / after" reads
// side by side), JSON, and the angle histogram as an SVG picture (as the histograms of the
// paper's Table 1, with the 60 degree position marked in red).

#ifndef POISSON_REMESH_IO_WRITE_QUALITY_REPORT_H
#define POISSON_REMESH_IO_WRITE_QUALITY_REPORT_H

#include <Poisson_remesh/quality_report.h>
#include <Poisson_remesh/internal/xml_escape.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <iomanip>
#include <ostream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace Poisson_remesh {

/// Reports with their labels ("input", "remeshed", ...), one column each in the outputs below.
typedef std::vector<std::pair<std::string, Quality_report>> Labelled_quality_reports;

namespace internal {

inline std::string format_double(double x, int precision = 6)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*g", precision, x);
  return buf;
}

inline std::string json_escape(const std::string& s)
{
  std::string out;
  for(char c : s) {
    if(c == '"' || c == '\\') { out += '\\'; out += c; }
    else if(static_cast<unsigned char>(c) < 0x20) { char buf[8]; std::snprintf(buf, sizeof(buf), "\\u%04x", c); out += buf; }
    else out += c;
  }
  return out;
}

} // namespace internal

/// One row per figure, one column per report.
inline void write_quality_table(std::ostream& os, const Labelled_quality_reports& reports)
{
  typedef std::pair<std::string, std::function<std::string(const Quality_report&)>> Row;
  using internal::format_double;
  auto count = [](std::size_t n) { return std::to_string(n); };
  const std::vector<Row> rows = {
    {"vertices", [&](const Quality_report& r) { return count(r.number_of_vertices); }},
    {"faces", [&](const Quality_report& r) { return count(r.number_of_faces); }},
    {"components", [&](const Quality_report& r) { return count(r.number_of_components); }},
    {"Euler characteristic", [](const Quality_report& r) { return std::to_string(r.euler_characteristic); }},
    {"genus", [](const Quality_report& r) { return std::to_string(r.genus); }},
    {"border edges", [&](const Quality_report& r) { return count(r.number_of_border_edges); }},
    {"min angle (deg)", [](const Quality_report& r) { return format_double(r.min_angle, 5); }},
    {"min angle away from corners (deg)", [](const Quality_report& r) {
       return r.min_angle_away_from_sharp_corners ? format_double(*r.min_angle_away_from_sharp_corners, 5) : std::string("-"); }},
    {"mean min angle (deg)", [](const Quality_report& r) { return format_double(r.mean_min_angle, 5); }},
    {"max angle (deg)", [](const Quality_report& r) { return format_double(r.max_angle, 5); }},
    {"min angle < 30 deg (%)", [](const Quality_report& r) { return format_double(100 * r.share_min_angle_below_30, 4); }},
    {"Q min (Frey-Borouchaki)", [](const Quality_report& r) { return format_double(r.min_shape_quality, 4); }},
    {"Q mean", [](const Quality_report& r) { return format_double(r.mean_shape_quality, 4); }},
    {"irregular vertices (%)", [](const Quality_report& r) { return format_double(100 * r.irregular_share, 4); }},
    {"degenerate faces", [&](const Quality_report& r) { return count(r.number_of_degenerate_faces); }},
    {"self-intersecting pairs", [&](const Quality_report& r) {
       return r.self_intersections_checked ? count(r.number_of_self_intersecting_face_pairs) : std::string("not checked"); }},
    {"  away from the input's own", [&](const Quality_report& r) {
       return r.number_of_self_intersecting_face_pairs_away_from_reference_ones ? count(*r.number_of_self_intersecting_face_pairs_away_from_reference_ones) : std::string("-"); }},
    {"Hausdorff / diagonal", [](const Quality_report& r) {
       if(!r.hausdorff) return std::string("-");
       // (with its error bound when that is coarser than the figure's last digit)
       std::string text = format_double(*r.hausdorff, 4);
       if(r.hausdorff_sampled && r.hausdorff_error_bound) text += " (sampled, < +" + format_double(*r.hausdorff_error_bound, 3) + ")";
       else if(r.hausdorff_error_bound && *r.hausdorff_error_bound > 1e-4) text += " +-" + format_double(*r.hausdorff_error_bound, 4);
       return text; }},
  };
  std::size_t label_width = 0;
  for(const Row& row : rows) label_width = std::max(label_width, row.first.size());
  std::vector<std::size_t> widths;
  for(const auto& rep : reports) {
    std::size_t w = rep.first.size();
    for(const Row& row : rows) w = std::max(w, row.second(rep.second).size());
    widths.push_back(w + 2);
  }
  os << std::left << std::setw(int(label_width + 2)) << "";
  for(std::size_t i = 0; i < reports.size(); ++i) os << std::right << std::setw(int(widths[i])) << reports[i].first;
  os << "\n";
  for(const Row& row : rows) {
    os << std::left << std::setw(int(label_width + 2)) << row.first;
    for(std::size_t i = 0; i < reports.size(); ++i) os << std::right << std::setw(int(widths[i])) << row.second(reports[i].second);
    os << "\n";
  }
  // valence histogram on one line per report
  for(const auto& rep : reports) {
    os << "valences (" << rep.first << "):";
    for(const auto& kv : rep.second.valence_histogram) os << " " << kv.first << ":" << kv.second;
    os << "\n";
  }
}

/// The report as a JSON object (no trailing newline).
inline std::string to_json(const Quality_report& r, const std::string& indent = "  ")
{
  std::ostringstream os;
  os << std::setprecision(17);
  const std::string in = indent + "  ";
  os << "{\n"
     << in << "\"vertices\": " << r.number_of_vertices << ",\n"
     << in << "\"edges\": " << r.number_of_edges << ",\n"
     << in << "\"faces\": " << r.number_of_faces << ",\n"
     << in << "\"components\": " << r.number_of_components << ",\n"
     << in << "\"euler_characteristic\": " << r.euler_characteristic << ",\n"
     << in << "\"genus\": " << r.genus << ",\n"
     << in << "\"border_edges\": " << r.number_of_border_edges << ",\n"
     << in << "\"border_cycles\": " << r.number_of_border_cycles << ",\n"
     << in << "\"min_angle_deg\": " << r.min_angle << ",\n"
     << in << "\"mean_min_angle_deg\": " << r.mean_min_angle << ",\n"
     << in << "\"max_angle_deg\": " << r.max_angle << ",\n"
     << in << "\"share_min_angle_below_30\": " << r.share_min_angle_below_30 << ",\n"
     << in << "\"min_shape_quality\": " << r.min_shape_quality << ",\n"
     << in << "\"mean_shape_quality\": " << r.mean_shape_quality << ",\n"
     << in << "\"irregular_share\": " << r.irregular_share << ",\n"
     << in << "\"degenerate_faces\": " << r.number_of_degenerate_faces << ",\n"
     << in << "\"bbox_diagonal\": " << r.bbox_diagonal << ",\n";
  // (a figure that was not computed is null)
  auto optional_field = [&](const char* name, const auto& value) {
    os << in << "\"" << name << "\": ";
    if(value) os << *value; else os << "null";
    os << ",\n";
  };
  optional_field("self_intersecting_face_pairs",
           r.self_intersections_checked ? std::optional<std::size_t>(r.number_of_self_intersecting_face_pairs) : std::nullopt);
  optional_field("reference_self_intersecting_face_pairs", r.number_of_reference_self_intersecting_face_pairs);
  optional_field("self_intersecting_face_pairs_away_from_reference_ones", r.number_of_self_intersecting_face_pairs_away_from_reference_ones);
  optional_field("min_angle_away_from_sharp_corners_deg", r.min_angle_away_from_sharp_corners);
  optional_field("hausdorff_over_diagonal", r.hausdorff);
  optional_field("hausdorff_absolute", r.hausdorff_absolute);
  optional_field("hausdorff_error_bound_over_diagonal", r.hausdorff_error_bound);
  if(r.hausdorff) os << in << "\"hausdorff_sampled\": " << (r.hausdorff_sampled ? "true" : "false") << ",\n";
  os << in << "\"valence_histogram\": {";
  bool first = true;
  for(const auto& kv : r.valence_histogram) { os << (first ? "" : ", ") << "\"" << kv.first << "\": " << kv.second; first = false; }
  os << "},\n" << in << "\"angle_histogram_bin_width_deg\": " << r.angle_histogram_bin_width << ",\n"
     << in << "\"angle_histogram\": [";
  for(std::size_t i = 0; i < r.angle_histogram.size(); ++i) os << (i ? ", " : "") << r.angle_histogram[i];
  os << "]\n" << indent << "}";
  return os.str();
}

/// Several labelled reports as one JSON object {"label": {...}, ...}.
inline void write_quality_json(std::ostream& os, const Labelled_quality_reports& reports)
{
  os << "{\n";
  for(std::size_t i = 0; i < reports.size(); ++i)
    os << "  \"" << internal::json_escape(reports[i].first) << "\": " << to_json(reports[i].second, "  ")
       << (i + 1 < reports.size() ? ",\n" : "\n");
  os << "}\n";
}

/// The angle histograms (share of all angles per bin), one panel per report, 60 degrees in red.
inline void write_angle_histogram_svg(std::ostream& os, const Labelled_quality_reports& reports)
{
  const double W = 720, panel_h = 180, left = 50, right = 20, top = 30, bottom = 30;
  const double H = reports.size() * panel_h + 10;
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
     << "\" viewBox=\"0 0 " << W << " " << H << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
     << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for(std::size_t k = 0; k < reports.size(); ++k) {
    const Quality_report& r = reports[k].second;
    const double y0 = k * panel_h + top, plot_h = panel_h - top - bottom, plot_w = W - left - right;
    std::size_t total = 0, peak = 1;
    for(std::size_t c : r.angle_histogram) { total += c; peak = std::max(peak, c); }
    const double peak_share = total ? double(peak) / double(total) : 1;
    os << "<text x=\"" << left << "\" y=\"" << y0 - 10 << "\" font-weight=\"bold\">"
       << internal::xml_escape(reports[k].first) << "</text>\n"
       << "<text x=\"" << W - right << "\" y=\"" << y0 - 10 << "\" text-anchor=\"end\">min "
       << internal::format_double(r.min_angle, 4) << "\xC2\xB0, mean min " << internal::format_double(r.mean_min_angle, 4)
       << "\xC2\xB0, irregular " << internal::format_double(100 * r.irregular_share, 3) << "%</text>\n";
    const std::size_t n = r.angle_histogram.size();
    for(std::size_t i = 0; i < n && total; ++i) {
      const double share = double(r.angle_histogram[i]) / double(total);
      const double h = plot_h * share / peak_share;
      const double x = left + plot_w * double(i) / double(n);
      os << "<rect x=\"" << x << "\" y=\"" << y0 + plot_h - h << "\" width=\"" << std::max(0.5, plot_w / double(n) - 0.5)
         << "\" height=\"" << h << "\" fill=\"#4a6fa5\"/>\n";
    }
    const double x60 = left + plot_w * 60.0 / 180.0;
    os << "<line x1=\"" << x60 << "\" y1=\"" << y0 << "\" x2=\"" << x60 << "\" y2=\"" << y0 + plot_h
       << "\" stroke=\"red\" stroke-width=\"1.5\"/>\n"
       << "<line x1=\"" << left << "\" y1=\"" << y0 + plot_h << "\" x2=\"" << left + plot_w << "\" y2=\"" << y0 + plot_h
       << "\" stroke=\"black\"/>\n";
    for(int deg = 0; deg <= 180; deg += 30)
      os << "<text x=\"" << left + plot_w * deg / 180.0 << "\" y=\"" << y0 + plot_h + 15
         << "\" text-anchor=\"middle\">" << deg << "\xC2\xB0</text>\n";
    os << "<text x=\"" << left - 5 << "\" y=\"" << y0 + 10 << "\" text-anchor=\"end\">"
       << internal::format_double(100 * peak_share, 3) << "%</text>\n";
  }
  os << "</svg>\n";
}

} // namespace Poisson_remesh

#endif // POISSON_REMESH_IO_WRITE_QUALITY_REPORT_H
