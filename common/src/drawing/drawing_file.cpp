#include "reliefkit/drawing/drawing_file.h"

#include <nlohmann/json.hpp>

#include <cmath>

#include "reliefkit/base/scale.h"

namespace reliefkit {

namespace {

using json = nlohmann::ordered_json;  // keys in the order written: id first

const char* kFormat = "reliefkit-drawing-interpretation";

const char* profile_name(CurveProfile p) {
  return p == CurveProfile::Ridge ? "ridge" : p == CurveProfile::Valley ? "valley" : "step";
}

json shape_json(const std::vector<Vec2>& shape) {
  json a = json::array();
  for (const Vec2& q : shape) a.push_back({q.x(), q.y()});
  return a;
}

// A point rounded to 0.1 px.
json point(const Vec2& p) {
  return json::array({std::round(p.x() * 10) / 10, std::round(p.y() * 10) / 10});
}

}  // namespace

std::string interpretation_to_json(const std::string& drawing_name, const DrawingCurves& dc, const LineDetectionParams& det,
                                   const DrawingInterpretation& di) {
  json j;
  j["format"] = kFormat;
  j["version"] = 1;
  j["drawing"] = drawing_name;
  j["image_size"] = {dc.width, dc.height};
  j["line_detection"] = {{"sigma_px", det.sigma}, {"min_length_px", det.min_length}};
  j["help"] =
      "Curve ids follow the extraction with these parameters. Per curve: direction 'auto', 'left-lower' or "
      "'right-lower' (seen along the curve from start to end, image y down); weight 0 (automatic) or the least step "
      "in levels (for a ridge or valley: its height in levels); profile 'step', 'ridge' or 'valley', with an optional "
      "free-form 'shape' [[t, value], ...] (t from -1, the left side, to 1); or 'spans': [{'from': 0, 'to': 0.5, "
      "'profile': ...}, ...] for several profiles along the curve (arc-length fractions). step = level right - "
      "level left as interpreted. 'shading': true marks a stroke of hatching, left out of the regions; give it a "
      "direction, weight or profile to make it a line of the relief. Format: docs/drawing_recon.md.";
  json curves = json::array();
  for (size_t k = 0; k < dc.curves.size(); ++k) {
    const auto& c = dc.curves[k];
    double len = 0;
    for (size_t i = 1; i < c.size(); ++i) len += (c[i] - c[i - 1]).norm();
    json e;
    e["id"] = int(k);
    e["start"] = point(c.front());
    e["end"] = point(c.back());
    e["length_px"] = std::round(len * 10) / 10;
    const bool have = k < di.sides.size();
    e["left_region"] = have ? di.sides[k][0] : -1;
    e["right_region"] = have ? di.sides[k][1] : -1;
    e["step"] = k < di.step.size() ? di.step[k] : 0;
    if (k < di.shading.size() && di.shading[k]) e["shading"] = true;
    e["direction"] = "auto";
    e["weight"] = k < di.weight.size() ? di.weight[k] : 0;
    const bool spans = k < di.profiles.size() && !di.profiles[k].empty();
    if (!spans) {
      e["profile"] = "step";
    } else if (di.profiles[k].size() == 1 && di.profiles[k][0].from == 0 && di.profiles[k][0].to == 1) {
      e["profile"] = profile_name(di.profiles[k][0].profile);
      if (!di.profiles[k][0].shape.empty()) e["shape"] = shape_json(di.profiles[k][0].shape);
    } else {
      json list = json::array();
      for (const ProfileSpan& sp : di.profiles[k]) {
        json x = {{"from", sp.from}, {"to", sp.to}, {"profile", profile_name(sp.profile)}};
        if (!sp.shape.empty()) x["shape"] = shape_json(sp.shape);
        list.push_back(x);
      }
      e["spans"] = list;
    }
    curves.push_back(e);
  }
  json regions = json::array();
  for (int r = 0; r < int(di.region_height.size()); ++r) regions.push_back({{"id", r}, {"level", di.region_height[size_t(r)]}});
  // One curve (region) per line, so that a curve's entry reads and edits as one line.
  std::string out = "{\n";
  for (auto it = j.begin(); it != j.end(); ++it) out += " " + json(it.key()).dump() + ": " + it.value().dump() + ",\n";
  auto list = [&](const char* name, const json& items, bool last) {
    out += std::string(" \"") + name + "\": [\n";
    for (size_t i = 0; i < items.size(); ++i) out += "  " + items[i].dump(-1, ' ', false) + (i + 1 < items.size() ? ",\n" : "\n");
    out += std::string(" ]") + (last ? "\n" : ",\n");
  };
  list("curves", curves, false);
  list("regions", regions, true);
  return out + "}\n";
}

namespace {
std::vector<CurveOverride> read_overrides(const std::string& text, const DrawingCurves& dc);
}

std::vector<CurveOverride> overrides_from_json(const std::string& text, const DrawingCurves& dc) {
  try {
    return read_overrides(text, dc);
  } catch (const nlohmann::json::exception& e) {  // a value of the wrong type
    throw InputError(std::string("The interpretation file has a value of the wrong type: ") + e.what());
  }
}

namespace {
// A profile ("profile" and its optional "shape") into `sp`; true when it is not the plain step.
bool read_span(const json& x, int id, ProfileSpan& sp) {
  const std::string prof = x.value("profile", "step");
  if (prof == "ridge")
    sp.profile = CurveProfile::Ridge;
  else if (prof == "valley")
    sp.profile = CurveProfile::Valley;
  else if (prof != "step")
    throw InputError("Curve " + std::to_string(id) + ": profile \"" + prof + "\" is not one of step, ridge, valley.");
  if (x.contains("shape")) {
    if (!x["shape"].is_array() || x["shape"].size() < 2)
      throw InputError("Curve " + std::to_string(id) + ": a shape is a list of at least two [t, value] pairs.");
    for (const json& q : x["shape"]) {
      if (!q.is_array() || q.size() != 2 || !q[0].is_number() || !q[1].is_number())
        throw InputError("Curve " + std::to_string(id) + ": a shape is a list of [t, value] pairs of numbers.");
      sp.shape.push_back(Vec2(q[0].get<double>(), q[1].get<double>()));
    }
  }
  return prof != "step" || !sp.shape.empty();
}

// The curve id of an entry, checked against the drawing: known, and the same curve (its end points
// within 2 px of what this extraction found).
int entry_curve(const json& e, const DrawingCurves& dc) {
  if (!e.is_object() || !e.contains("id") || !e["id"].is_number_integer())
    throw InputError("The interpretation file has a curve entry without a whole-number \"id\".");
  const int id = e["id"].get<int>(), nc = int(dc.curves.size());
  if (id < 0 || id >= nc)
    throw InputError("The interpretation file names curve " + std::to_string(id) + ", but this drawing has curves 0 to " +
                     std::to_string(nc - 1) + ". Was it written with other line-detection parameters?");
  auto near = [](const json& a, const Vec2& p) {
    return a.is_array() && a.size() == 2 && a[0].is_number() && a[1].is_number() &&
           std::hypot(a[0].get<double>() - p.x(), a[1].get<double>() - p.y()) <= 2.0;
  };
  if (e.contains("start") && !(near(e["start"], dc.curves[size_t(id)].front()) && near(e["end"], dc.curves[size_t(id)].back())))
    throw InputError("Curve " + std::to_string(id) +
                     " of the interpretation file does not match this drawing's curve " + std::to_string(id) +
                     " (its end points differ): the file was written for another drawing or other line-detection parameters.");
  return id;
}

// One curve entry; false when it asks for nothing beyond the automatic interpretation.
bool read_override(const json& e, const DrawingCurves& dc, CurveOverride& o) {
  const int id = o.curve = entry_curve(e, dc);
  const std::string dir = e.value("direction", "auto");
  if (dir == "left-lower")
    o.direction = CurveOverride::Direction::LeftLower;
  else if (dir == "right-lower")
    o.direction = CurveOverride::Direction::RightLower;
  else if (dir != "auto")
    throw InputError("Curve " + std::to_string(id) + ": direction \"" + dir + "\" is not one of auto, left-lower, right-lower.");
  if (e.contains("weight")) {
    if (!e["weight"].is_number_integer()) throw InputError("Curve " + std::to_string(id) + ": the weight must be a whole number.");
    o.weight = e["weight"].get<int>();
  }
  // Profiles: "profile" (+ "shape") for the whole curve, or "spans" of several.
  bool custom = false;
  if (e.contains("spans")) {
    if (!e["spans"].is_array()) throw InputError("Curve " + std::to_string(id) + ": \"spans\" must be a list.");
    for (const json& x : e["spans"]) {
      ProfileSpan sp;
      read_span(x, id, sp);
      sp.from = x.value("from", 0.0);
      sp.to = x.value("to", 1.0);
      o.spans.push_back(sp);
    }
    custom = !o.spans.empty();
  } else {
    ProfileSpan sp;
    if (read_span(e, id, sp)) o.spans.push_back(sp), custom = true;
  }
  return o.direction != CurveOverride::Direction::Auto || o.weight != 0 || custom;
}

std::vector<CurveOverride> read_overrides(const std::string& text, const DrawingCurves& dc) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError(std::string("The interpretation file is not valid JSON: ") + e.what());
  }
  if (!j.is_object() || j.value("format", "") != kFormat || !j.contains("curves") || !j["curves"].is_array())
    throw InputError("The interpretation file is not a ReliefKit drawing interpretation (its \"format\" must be \"" +
                     std::string(kFormat) + "\" and it must list \"curves\").");
  std::vector<CurveOverride> out;
  for (const json& e : j["curves"]) {
    CurveOverride o;
    if (read_override(e, dc, o)) out.push_back(o);
  }
  return out;
}
}  // namespace

}  // namespace reliefkit
