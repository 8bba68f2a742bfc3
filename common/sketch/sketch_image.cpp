#include "common/sketch/sketch_image.hpp"

#include "common/base/errors.hpp"
#include "common/base/image_budget.hpp"
#include "common/sketch/mark_moments.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace physarum {
namespace {

enum Pixel : std::uint8_t { kBackground = 0, kDark = 1, kRed = 2 };

struct Picture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> kind;  // Pixel, row-major from the top row
};

Picture read_picture(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path + ": cannot read the sketch image (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1) throw InputError(path + ": the sketch image is empty");
  check_image_budget(spec.width, spec.height, path, "sketch");
  const int channels = spec.nchannels;
  std::vector<float> pixels(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height) * static_cast<size_t>(channels));
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw InputError(path + ": cannot read the sketch image (" + in->geterror() + ")");
  Picture p{spec.width, spec.height, std::vector<std::uint8_t>(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height))};
  const bool colour = channels >= 3, alpha = channels == 2 || channels == 4;
  for (size_t i = 0; i < p.kind.size(); ++i) {
    const float* c = &pixels[i * static_cast<size_t>(channels)];
    const double a = alpha ? c[channels - 1] : 1.0;
    auto over_white = [a](double v) { return a * v + (1.0 - a); };
    const double r = over_white(c[0]), g = over_white(colour ? c[1] : c[0]), b = over_white(colour ? c[2] : c[0]);
    if (colour && r > 0.5 && g < 0.35 && b < 0.35) p.kind[i] = kRed;
    else if (0.2126 * r + 0.7152 * g + 0.0722 * b < 0.5) p.kind[i] = kDark;
  }
  return p;
}

// Labels the connected groups of pixels of one kind (8- or 4-connected) with 1, 2, ...; 0 elsewhere.
// An explicit stack: a mark as large as the image does not recurse.
int label_groups(const Picture& p, std::uint8_t kind, bool diagonal, std::vector<int>& label) {
  label.assign(p.kind.size(), 0);
  int groups = 0;
  std::vector<int> stack;
  for (int start = 0; start < static_cast<int>(p.kind.size()); ++start) {
    if (p.kind[static_cast<size_t>(start)] != kind || label[static_cast<size_t>(start)] != 0) continue;
    label[static_cast<size_t>(start)] = ++groups;
    stack.push_back(start);
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      const int x = i % p.width, y = i / p.width;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if ((dx == 0 && dy == 0) || (!diagonal && dx != 0 && dy != 0)) continue;
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= p.width || ny >= p.height) continue;
          const int n = ny * p.width + nx;
          if (p.kind[static_cast<size_t>(n)] == kind && label[static_cast<size_t>(n)] == 0) {
            label[static_cast<size_t>(n)] = groups;
            stack.push_back(n);
          }
        }
    }
  }
  return groups;
}

struct Mark {
  MarkMoments drawn;      // the mark's own pixels
  MarkMoments enclosed;   // background it encloses (an outline's inside)
  std::vector<int> cells; // its pixels (row-major indices)
  bool red = false;
};

// Ramanujan's perimeter of an ellipse with semi-axes a, b.
double ellipse_perimeter(double a, double b) {
  const double h = (a - b) * (a - b) / ((a + b) * (a + b));
  return M_PI * (a + b) * (1.0 + 3.0 * h / (10.0 + std::sqrt(4.0 - 3.0 * h)));
}

SketchStroke stroke_of(const Mark& mark, const Picture& p, double side) {
  const MarkMoments& m = mark.drawn;
  const MarkMoments::Ellipse e = m.ellipse();
  const double t = e.orientation * M_PI / 180.0;
  const Eigen::Vector2d d(std::cos(t), std::sin(t));
  double lo = 0.0, hi = 0.0;
  for (const int i : mark.cells) {
    const Eigen::Vector2d q((i % p.width + 0.5) * side, (p.height - i / p.width - 0.5) * side);
    const double s = (q - e.center).dot(d);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  SketchStroke stroke;
  stroke.points = {e.center + (lo - 0.5 * side) * d, e.center + (hi + 0.5 * side) * d};
  const double length = hi - lo + side;
  stroke.width = m.area() / length;
  stroke.width_class = std::clamp(static_cast<int>(std::lround(stroke.width / 0.01)), 1, kStrokeWidthClasses);
  return stroke;
}

}  // namespace

Sketch sketch_from_image(const std::string& path) {
  const Picture p = read_picture(path);
  const double side = 1.0 / p.width;  // a pixel's side in window units
  auto cell = [&](int i) { return Eigen::Vector2d((i % p.width + 0.5) * side, (p.height - i / p.width - 0.5) * side); };

  std::vector<int> dark, red, background;
  const int dark_count = label_groups(p, kDark, true, dark), red_count = label_groups(p, kRed, true, red);
  std::vector<Mark> marks(static_cast<size_t>(dark_count + red_count));
  for (int i = 0; i < static_cast<int>(p.kind.size()); ++i) {
    const int id = dark[static_cast<size_t>(i)] ? dark[static_cast<size_t>(i)] - 1
                   : red[static_cast<size_t>(i)] ? dark_count + red[static_cast<size_t>(i)] - 1 : -1;
    if (id < 0) continue;
    marks[static_cast<size_t>(id)].drawn.add_cell(cell(i), side);
    marks[static_cast<size_t>(id)].cells.push_back(i);
    marks[static_cast<size_t>(id)].red = id >= dark_count;
  }
  // Background groups that do not reach the border are enclosed: they belong to the dark mark
  // around them (4-connected background, so a diagonal gap in an outline does not leak).
  const int background_count = label_groups(p, kBackground, false, background);
  std::vector<int> owner(static_cast<size_t>(background_count) + 1, -1);  // -1 unknown, -2 open
  for (int i = 0; i < static_cast<int>(p.kind.size()); ++i) {
    const int b = background[static_cast<size_t>(i)];
    if (b == 0) continue;
    const int x = i % p.width, y = i / p.width;
    if (x == 0 || y == 0 || x == p.width - 1 || y == p.height - 1) owner[static_cast<size_t>(b)] = -2;
    if (owner[static_cast<size_t>(b)] != -1) continue;
    for (const int n : {i - 1, i + 1, i - p.width, i + p.width})
      if (n >= 0 && n < static_cast<int>(p.kind.size()) && dark[static_cast<size_t>(n)] != 0) {
        owner[static_cast<size_t>(b)] = dark[static_cast<size_t>(n)] - 1;
        break;
      }
  }
  for (int i = 0; i < static_cast<int>(p.kind.size()); ++i) {
    const int b = background[static_cast<size_t>(i)];
    if (b != 0 && owner[static_cast<size_t>(b)] >= 0) marks[static_cast<size_t>(owner[static_cast<size_t>(b)])].enclosed.add_cell(cell(i), side);
  }

  Sketch sketch;
  sketch.source = path;
  sketch.window = Eigen::Vector2d(1.0, static_cast<double>(p.height) / p.width);
  for (const Mark& mark : marks) {
    MarkMoments all = mark.drawn;
    all.add(mark.enclosed);
    const MarkMoments::Ellipse e = all.ellipse();
    if (static_cast<int>(mark.cells.size()) < kMinMarkPixels)
      throw InputError(path + ": the mark at (" + std::to_string(e.center.x()) + ", " + std::to_string(e.center.y()) +
                       ") is " + std::to_string(mark.cells.size()) + " pixels; a mark needs " + std::to_string(kMinMarkPixels) +
                       " or more (about 5 x 4) to be measured: draw it larger, or remove it");
    const double fill = all.area() / (M_PI * e.major * e.minor);
    const bool stroke = mark.red || e.minor < kStrokeAspect * e.major || fill < kStrokeFill;
    if (stroke) {
      sketch.strokes.push_back(stroke_of(mark, p, side));
      continue;
    }
    SketchSpot spot{e.center, e.major, e.minor, e.orientation};
    if (mark.enclosed.area() > 0.0) {
      // An outline: its line is its drawn area over its length, and the ellipse the user meant runs
      // along the middle of the line (two passes: the length depends on the radii).
      double width = mark.drawn.area() / ellipse_perimeter(e.major, e.minor);
      width = mark.drawn.area() / ellipse_perimeter(e.major - width / 2, e.minor - width / 2);
      spot.major = std::max(e.major - width / 2, side);
      spot.minor = std::max(e.minor - width / 2, side);
    }
    sketch.spots.push_back(spot);
  }
  if (sketch.spots.empty() && sketch.strokes.empty())
    throw InputError(path + ": no marks (dark marks on a light background: spots and strokes; red marks are strokes)");
  return sketch;
}

}  // namespace physarum
