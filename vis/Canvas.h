// An 8-bit RGB picture, row 0 at the bottom (as OpenGL and VTK images), with what the overlay of
// a scene needs: filled rectangles and text rasterised by VTK's FreeType tools. Text is not
// thread-safe (VTK's font cache): draw from one thread.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace anode {

using RGB = std::array<double, 3>;  // each in [0, 1]

class Canvas {
 public:
  enum class Align {
    Start,
    Centre,
    End
  };  // of the text box against (x, y): left/bottom, centre, right/top

  Canvas(int width, int height, const RGB& fill);
  int width() const { return width_; }
  int height() const { return height_; }
  unsigned char* pixel(int x, int y) { return &rgb_[3 * (static_cast<size_t>(y) * width_ + x)]; }
  const unsigned char* pixel(int x, int y) const {
    return &rgb_[3 * (static_cast<size_t>(y) * width_ + x)];
  }
  const std::vector<unsigned char>& data() const { return rgb_; }
  std::vector<unsigned char>& data() { return rgb_; }

  // Fills [x0, x1) x [y0, y1), clipped to the canvas.
  void fillRect(int x0, int y0, int x1, int y1, const RGB& colour);
  // Draws one line of text of `size` pixels with its box aligned against (x, y).
  void text(const std::string& s, int x, int y, int size, const RGB& colour, Align h = Align::Start,
            Align v = Align::Start);
  // Width and height in pixels of a line of text.
  static std::array<int, 2> textSize(const std::string& s, int size);

 private:
  int width_, height_;
  std::vector<unsigned char> rgb_;
};

// Writes the canvas as a PNG (vtkPNGWriter), under a temporary name then renamed.
void writePNG(const Canvas& canvas, const std::string& path);

}  // namespace anode
