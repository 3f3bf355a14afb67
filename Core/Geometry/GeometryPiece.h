// Geometry pieces of <geom_object> (UINTAH_UPS.md §2.8). inside() uses closed sets, as Uintah does.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "Core/Math/Types.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

// An axis-aligned box holding a piece (empty when lo > hi in some direction).
struct Bounds {
  Vec3 lo, hi;
};

class GeometryPiece {
 public:
  virtual ~GeometryPiece() = default;
  virtual bool inside(const Vec3& x) const = 0;
  virtual std::string type() const = 0;
  // A box containing every point inside() accepts (not necessarily the smallest).
  virtual Bounds bounds() const = 0;
};

using GeometryPieceP = std::shared_ptr<const GeometryPiece>;

struct BoxPiece : GeometryPiece {
  Vec3 lo, hi;
  bool inside(const Vec3& x) const override {
    return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
  }
  std::string type() const override { return "box"; }
  Bounds bounds() const override { return {lo, hi}; }
};

struct CylinderPiece : GeometryPiece {
  Vec3 bottom, top;
  double radius = 0;
  bool inside(const Vec3& x) const override;
  std::string type() const override { return "cylinder"; }
  Bounds bounds() const override;
};

struct SpherePiece : GeometryPiece {
  Vec3 origin;
  double radius = 0;
  bool inside(const Vec3& x) const override {
    return (x - origin).squaredNorm() <= radius * radius;
  }
  std::string type() const override { return "sphere"; }
  Bounds bounds() const override { return {origin.array() - radius, origin.array() + radius}; }
};

struct UnionPiece : GeometryPiece {
  std::vector<GeometryPieceP> pieces;
  bool inside(const Vec3& x) const override;
  std::string type() const override { return "union"; }
  Bounds bounds() const override;
};

struct IntersectionPiece : GeometryPiece {
  std::vector<GeometryPieceP> pieces;
  bool inside(const Vec3& x) const override;
  std::string type() const override { return "intersection"; }
  Bounds bounds() const override;
};

struct DifferencePiece : GeometryPiece {
  GeometryPieceP first, second;
  bool inside(const Vec3& x) const override { return first->inside(x) && !second->inside(x); }
  std::string type() const override { return "difference"; }
  Bounds bounds() const override { return first->bounds(); }
};

// Builds pieces and resolves labelled references across the whole input.
class GeometryPieceFactory {
 public:
  // True if `tag` names a geometry piece this factory knows (supported or not).
  static bool isPieceTag(const std::string& tag);
  GeometryPieceP create(const PSNode& node);

 private:
  std::map<std::string, GeometryPieceP> labelled_;
};

}  // namespace anode
