// What the drawing filters share in their MeshLab adapters: the drawing-image parameter, the DPI
// and scale that set a pixel's size, and reading the image.
#pragma once

#include <opencv2/core.hpp>

#include "params.h"

namespace reliefkit::ml {

/// The image files the drawing filters read (PNG, JPEG, TIFF, BMP).
const QStringList& drawing_image_extensions();

/// The parameter "drawing" (label "Drawing image") with the filter's own help.
void add_drawing_image_parameter(RichParameterList& par, const QString& help);

/// The parameters "dpi" (300) and "scale" (1): one pixel = 25.4 / DPI x scale millimetres.
void add_dpi_and_scale_parameters(RichParameterList& par);

/// Millimetres per pixel of the image as drawn, from "dpi" and "scale" (refused out of range).
double read_pixel_mm(FilterCall& call);

/// The image of parameter "drawing" (refused when none is given, missing or unreadable); one larger
/// than kMaxDrawingPixels is read reduced, said in the log, and `pixel_mm` is corrected for it.
cv::Mat read_drawing_parameter(FilterCall& call, double& pixel_mm, QString* path = nullptr);

}  // namespace reliefkit::ml
