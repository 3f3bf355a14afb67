#include "vis/Canvas.h"

#include <vtkFreeTypeTools.h>
#include <vtkImageData.h>
#include <vtkPNGWriter.h>
#include <vtkSmartPointer.h>
#include <vtkStdString.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "Core/Util/AtomicFile.h"

namespace anode {

namespace {

unsigned char toByte(double v) {
  return static_cast<unsigned char>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
}

vtkSmartPointer<vtkTextProperty> textProperty(int size, const RGB& colour) {
  auto p = vtkSmartPointer<vtkTextProperty>::New();
  p->SetFontFamilyToArial();
  p->SetFontSize(size);
  p->SetColor(colour[0], colour[1], colour[2]);
  p->SetJustificationToLeft();
  p->SetVerticalJustificationToBottom();
  return p;
}

}  // namespace

Canvas::Canvas(int width, int height, const RGB& fill)
    : width_(width), height_(height), rgb_(3 * width * height) {
  fillRect(0, 0, width, height, fill);
}

void Canvas::fillRect(int x0, int y0, int x1, int y1, const RGB& colour) {
  const unsigned char c[3] = {toByte(colour[0]), toByte(colour[1]), toByte(colour[2])};
  for (int y = std::max(y0, 0); y < std::min(y1, height_); ++y)
    for (int x = std::max(x0, 0); x < std::min(x1, width_); ++x) std::memcpy(pixel(x, y), c, 3);
}

std::array<int, 2> Canvas::textSize(const std::string& s, int size) {
  int box[4] = {0, 0, 0, 0};
  if (s.empty() || !vtkFreeTypeTools::GetInstance()->GetBoundingBox(textProperty(size, {0, 0, 0}),
                                                                    vtkStdString(s), 72, box))
    return {0, 0};
  return {box[1] - box[0] + 1, box[3] - box[2] + 1};
}

void Canvas::text(const std::string& s, int x, int y, int size, const RGB& colour, Align h,
                  Align v) {
  if (s.empty()) return;
  auto image = vtkSmartPointer<vtkImageData>::New();
  int dims[2] = {0, 0};
  if (!vtkFreeTypeTools::GetInstance()->RenderString(textProperty(size, colour), vtkStdString(s),
                                                     72, image, dims))
    throw std::runtime_error("VTK could not render the text '" + s + "'");
  // RenderString leaves the text box at the image's lower left corner, RGBA with coverage in alpha.
  int extent[6];
  image->GetExtent(extent);
  const int rowLength = extent[1] - extent[0] + 1;
  const auto* src = static_cast<const unsigned char*>(image->GetScalarPointer());
  const int left = h == Align::Start ? x : h == Align::Centre ? x - dims[0] / 2 : x - dims[0];
  const int bottom = v == Align::Start ? y : v == Align::Centre ? y - dims[1] / 2 : y - dims[1];
  for (int j = 0; j < dims[1]; ++j)
    for (int i = 0; i < dims[0]; ++i) {
      const int px = left + i, py = bottom + j;
      if (px < 0 || py < 0 || px >= width_ || py >= height_) continue;
      const unsigned char* t = src + 4 * (static_cast<size_t>(j) * rowLength + i);
      const double a = t[3] / 255.0;
      unsigned char* d = pixel(px, py);
      for (int c = 0; c < 3; ++c)
        d[c] = static_cast<unsigned char>(std::lround(a * t[c] + (1 - a) * d[c]));
    }
}

void writePNG(const Canvas& canvas, const std::string& path) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(canvas.width(), canvas.height(), 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  std::memcpy(image->GetScalarPointer(), canvas.data().data(), canvas.data().size());
  auto writer = vtkSmartPointer<vtkPNGWriter>::New();
  writer->SetInputData(image);
  writeAtomically(path, [&](const std::string& tmp) {
    writer->SetFileName(tmp.c_str());
    writer->Write();
    if (writer->GetErrorCode() != 0) throw std::runtime_error("VTK could not write " + tmp);
  });
}

}  // namespace anode
