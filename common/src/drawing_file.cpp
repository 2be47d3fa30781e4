#include "reliefkit/drawing_file.h"

#include <nlohmann/json.hpp>

#include <cmath>

#include "reliefkit/scale.h"

namespace reliefkit {

namespace {

using nlohmann::json;

const char* kFormat = "reliefkit-drawing-interpretation";

const char* profile_name(CurveProfile p) { return p == CurveProfile::Ridge ? "ridge" : p == CurveProfile::Valley ? "valley" : "step"; }

json point(const Vec2& p) { return json::array({std::round(p.x() * 10) / 10, std::round(p.y() * 10) / 10}); }

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
      "in levels (for a ridge or valley: its height in levels); profile 'step', 'ridge' or 'valley'. step = level "
      "right - level left as interpreted.";
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
    e["direction"] = "auto";
    e["weight"] = k < di.weight.size() ? di.weight[k] : 0;
    e["profile"] = profile_name(k < di.profile.size() ? di.profile[k] : CurveProfile::Step);
    curves.push_back(e);
  }
  j["curves"] = curves;
  json regions = json::array();
  for (int r = 0; r < int(di.region_height.size()); ++r) regions.push_back({{"id", r}, {"level", di.region_height[size_t(r)]}});
  j["regions"] = regions;
  return j.dump(1) + "\n";
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
  const int nc = int(dc.curves.size());
  std::vector<CurveOverride> out;
  for (const json& e : j["curves"]) {
    if (!e.is_object() || !e.contains("id") || !e["id"].is_number_integer())
      throw InputError("The interpretation file has a curve entry without a whole-number \"id\".");
    const int id = e["id"].get<int>();
    if (id < 0 || id >= nc)
      throw InputError("The interpretation file names curve " + std::to_string(id) + ", but this drawing has curves 0 to " +
                       std::to_string(nc - 1) + ". Was it written with other line-detection parameters?");
    // The same curve? Its end points must match what this extraction found (within 2 px).
    auto near = [](const json& a, const Vec2& p) {
      return a.is_array() && a.size() == 2 && a[0].is_number() && a[1].is_number() &&
             std::hypot(a[0].get<double>() - p.x(), a[1].get<double>() - p.y()) <= 2.0;
    };
    if (e.contains("start") && !(near(e["start"], dc.curves[size_t(id)].front()) && near(e["end"], dc.curves[size_t(id)].back())))
      throw InputError("Curve " + std::to_string(id) +
                       " of the interpretation file does not match this drawing's curve " + std::to_string(id) +
                       " (its end points differ): the file was written for another drawing or other line-detection parameters.");
    CurveOverride o;
    o.curve = id;
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
    const std::string prof = e.value("profile", "step");
    if (prof == "ridge")
      o.profile = CurveProfile::Ridge;
    else if (prof == "valley")
      o.profile = CurveProfile::Valley;
    else if (prof != "step")
      throw InputError("Curve " + std::to_string(id) + ": profile \"" + prof + "\" is not one of step, ridge, valley.");
    if (o.direction != CurveOverride::Direction::Auto || o.weight != 0 || o.profile != CurveProfile::Step) out.push_back(o);
  }
  return out;
}
}  // namespace

}  // namespace reliefkit
