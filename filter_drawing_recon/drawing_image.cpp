#include "drawing_image.h"

#include "reliefkit/drawing/line_drawing.h"

namespace reliefkit::ml {

const QStringList& drawing_image_extensions() {
  static const QStringList exts = {"*.png", "*.jpg", "*.jpeg", "*.tif", "*.tiff", "*.bmp"};
  return exts;
}

void add_drawing_image_parameter(RichParameterList& par, const QString& help) {
  par.addParam(ml::RichOpenFile("drawing", "", drawing_image_extensions(), "Drawing image", help));
}

void add_dpi_and_scale_parameters(RichParameterList& par) {
  par.addParam(RichFloat("dpi", 300.f, "Drawing resolution (DPI)",
                         "Dots per inch of the scan: with the scale it sets the size of a pixel on the object, "
                         "25.4 / DPI x scale millimetres."));
  par.addParam(RichFloat("scale", 1.f, "Drawing scale (object : drawing)",
                         "How many times larger the object is than its drawing (2 for a figure drawn at 1:2)."));
}

double read_pixel_mm(FilterCall& call) {
  const double dpi = read_float(call, "dpi", "Drawing resolution (DPI)", 1, 100000);
  const double scale = read_float(call, "scale", "Drawing scale (object : drawing)", 1e-6, 1e6);
  return 25.4 / dpi * scale;
}

cv::Mat read_drawing_parameter(FilterCall& call, double& pixel_mm, QString* path) {
  const QString file = call.params.getOpenFileName("drawing");
  if (path) *path = file;
  if (file.trimmed().isEmpty()) throw InputError("No drawing image was given: choose the image file in \"Drawing image\".");
  double reduction = 1;
  cv::Mat image = read_drawing_image(file.toStdString(), &reduction);
  pixel_mm /= reduction;
  if (reduction < 1)
    call.log(QString("The drawing has more than %1 million pixels: read reduced by %2 (pixel size %3 mm).")
                 .arg(kMaxDrawingPixels / 1e6, 0, 'f', 0)
                 .arg(reduction, 0, 'f', 3)
                 .arg(pixel_mm, 0, 'g', 4));
  return image;
}

}  // namespace reliefkit::ml
