#include "vis/ColourMap.h"

#include <vtkColorTransferFunction.h>

#include <algorithm>
#include <cmath>

namespace anode {

namespace {

// Viridis (van der Walt and Smith, matplotlib's default map, CC0) at nine equally spaced
// fractions; linear interpolation in RGB between them stays within 1/255 of the full map.
const double kViridis[9][3] = {
    {0.267004, 0.004874, 0.329415}, {0.282623, 0.140926, 0.457517}, {0.229739, 0.322361, 0.545706},
    {0.172719, 0.448791, 0.557885}, {0.127568, 0.566949, 0.550556}, {0.157851, 0.683765, 0.501686},
    {0.369214, 0.788888, 0.382914}, {0.678489, 0.863742, 0.189503}, {0.993248, 0.906157, 0.143936}};

vtkSmartPointer<vtkColorTransferFunction> transferFunction(ColourMapKind kind) {
  auto f = vtkSmartPointer<vtkColorTransferFunction>::New();
  switch (kind) {
    case ColourMapKind::Viridis:
      f->SetColorSpaceToRGB();
      for (int k = 0; k < 9; ++k)
        f->AddRGBPoint(k / 8.0, kViridis[k][0], kViridis[k][1], kViridis[k][2]);
      break;
    case ColourMapKind::BlueRed:
      // Moreland's diverging cool-to-warm map: blue, through a light grey, to red.
      f->SetColorSpaceToDiverging();
      f->AddRGBPoint(0.0, 0.230, 0.299, 0.754);
      f->AddRGBPoint(1.0, 0.706, 0.016, 0.150);
      break;
    case ColourMapKind::Grey:
      f->SetColorSpaceToRGB();
      f->AddRGBPoint(0.0, 0.0, 0.0, 0.0);
      f->AddRGBPoint(1.0, 1.0, 1.0, 1.0);
      break;
  }
  return f;
}

}  // namespace

ColourMap::ColourMap(ColourMapKind kind) : table_(vtkSmartPointer<vtkLookupTable>::New()) {
  const auto f = transferFunction(kind);
  table_->SetNumberOfTableValues(kEntries);
  table_->SetTableRange(0.0, 1.0);
  for (int i = 0; i < kEntries; ++i) {
    double rgb[3];
    f->GetColor(static_cast<double>(i) / (kEntries - 1), rgb);
    table_->SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0);
  }
}

std::array<double, 3> ColourMap::colour(double t) const {
  double rgb[3];
  table_->GetColor(std::clamp(t, 0.0, 1.0), rgb);
  return {rgb[0], rgb[1], rgb[2]};
}

std::vector<unsigned char> ColourMap::rgba8() const {
  std::vector<unsigned char> out(4 * kEntries);
  for (int i = 0; i < kEntries; ++i) {
    const double* v = table_->GetTableValue(i);
    for (int c = 0; c < 4; ++c)
      out[4 * i + c] = static_cast<unsigned char>(std::lround(255 * v[c]));
  }
  return out;
}

}  // namespace anode
