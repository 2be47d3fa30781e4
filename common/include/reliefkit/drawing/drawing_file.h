// ReliefKit — the interpretation file of a line drawing (JSON): what the automatic interpretation
// found for every curve, and the user's overrides read back from it (the thesis' fine-tuning
// interface, sect. 7.6, made scriptable). Format: docs/drawing_recon.md.
#pragma once

#include <string>

#include "reliefkit/drawing/drawing_interpretation.h"

namespace reliefkit {

/// The file's text: the drawing's name and size, the extraction's parameters, per curve its id,
/// end points, length, sides, step and the override fields (direction, weight, profile) with their
/// current values, per region its level and area.
std::string interpretation_to_json(const std::string& drawing_name, const DrawingCurves& curves,
                                   const LineDetectionParams& detection, const DrawingInterpretation& interpretation);

/// The overrides of an interpretation file (curves whose direction is not "auto", whose weight is
/// set, or whose profile is not "step"). Throws InputError when the text is not such a file, when it
/// was written for another extraction (a different curve count or different end points: the curve
/// ids would not name the same curves), or names unknown curves or values.
std::vector<CurveOverride> overrides_from_json(const std::string& text, const DrawingCurves& curves);

}  // namespace reliefkit
