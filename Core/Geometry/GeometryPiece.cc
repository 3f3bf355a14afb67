#include "Core/Geometry/GeometryPiece.h"

#include <algorithm>
#include <cmath>

#include "Core/Geometry/SmoothCylinder.h"

namespace anode {

bool CylinderPiece::inside(const Vec3& x) const {
  const Vec3 axis = top - bottom;
  const double along = (x - bottom).dot(axis);
  if (along < 0 || along > axis.squaredNorm()) return false;
  const Vec3 radial = (x - bottom) - along / axis.squaredNorm() * axis;
  return radial.squaredNorm() <= radius * radius;
}

Bounds CylinderPiece::bounds() const {
  return {bottom.cwiseMin(top).array() - radius, bottom.cwiseMax(top).array() + radius};
}

Bounds UnionPiece::bounds() const {
  Bounds b{Vec3::Constant(HUGE_VAL), Vec3::Constant(-HUGE_VAL)};
  for (const auto& p : pieces) {
    const Bounds q = p->bounds();
    b.lo = b.lo.cwiseMin(q.lo);
    b.hi = b.hi.cwiseMax(q.hi);
  }
  return b;
}

Bounds IntersectionPiece::bounds() const {
  Bounds b{Vec3::Constant(-HUGE_VAL), Vec3::Constant(HUGE_VAL)};
  for (const auto& p : pieces) {
    const Bounds q = p->bounds();
    b.lo = b.lo.cwiseMax(q.lo);
    b.hi = b.hi.cwiseMin(q.hi);
  }
  return b;
}

bool UnionPiece::inside(const Vec3& x) const {
  return std::any_of(pieces.begin(), pieces.end(), [&](const auto& p) { return p->inside(x); });
}

bool IntersectionPiece::inside(const Vec3& x) const {
  return std::all_of(pieces.begin(), pieces.end(), [&](const auto& p) { return p->inside(x); });
}

bool GeometryPieceFactory::isPieceTag(const std::string& tag) {
  static const char* known[] = {
      "box",  "cylinder",  "sphere", "union", "intersection", "difference",     "smoothcyl",  "tri",
      "cone", "ellipsoid", "torus",  "file",  "null",         "parallelepiped", "convex_hull"};
  return std::any_of(std::begin(known), std::end(known), [&](const char* k) { return tag == k; });
}

namespace {

void positive(const PSNode& node, const char* tag, double v) {
  if (!(v > 0)) node.requireChild(tag).fail("<" + std::string(tag) + "> must be positive");
}

}  // namespace

GeometryPieceP GeometryPieceFactory::create(const PSNode& node) {
  const std::string tag = node.name();
  std::optional<std::string> label = node.attribute("label");
  if (!label) label = node.attribute("name");
  const bool hasContent = node.hasChildren();
  if (label && !hasContent) {
    auto it = labelled_.find(*label);
    if (it == labelled_.end())
      node.fail("<" + tag + " label=\"" + *label +
                "\"> refers to a piece that is not defined before it");
    if (it->second->type() != tag)
      node.fail("<" + tag + " label=\"" + *label + "\"> refers to a " + it->second->type() +
                ", not a " + tag);
    return it->second;
  }
  if (label && labelled_.count(*label))
    node.fail("the label \"" + *label + "\" is already defined by another piece");

  auto childPieces = [&](const PSNode& n) {
    std::vector<GeometryPieceP> out;
    for (const PSNode& c : n.children()) {
      if (!isPieceTag(c.name())) c.fail("<" + c.name() + "> is not a geometry piece");
      out.push_back(create(c));
    }
    return out;
  };

  GeometryPieceP piece;
  if (tag == "box") {
    auto b = std::make_shared<BoxPiece>();
    b->lo = node.require<Vec3>("min");
    b->hi = node.require<Vec3>("max");
    if ((b->hi.array() < b->lo.array()).any())
      node.requireChild("max").fail("<max> must be >= <min>");
    piece = b;
  } else if (tag == "cylinder") {
    auto c = std::make_shared<CylinderPiece>();
    c->bottom = node.require<Vec3>("bottom");
    c->top = node.require<Vec3>("top");
    c->radius = node.require<double>("radius");
    positive(node, "radius", c->radius);
    if ((c->top - c->bottom).norm() == 0) node.requireChild("top").fail("<top> equals <bottom>");
    // End-face flags matter only to flux boundary conditions, which read them there.
    node.acceptInert("cylinder_end");
    node.acceptInert("axisymmetric_end");
    node.acceptInert("axisymmetric_side");
    piece = c;
  } else if (tag == "sphere") {
    auto s = std::make_shared<SpherePiece>();
    const PSNode origin = node.child("origin");
    s->origin = origin ? origin.value<Vec3>() : node.require<Vec3>("center");
    s->radius = node.require<double>("radius");
    positive(node, "radius", s->radius);
    piece = s;
  } else if (tag == "union") {
    auto u = std::make_shared<UnionPiece>();
    u->pieces = childPieces(node);
    if (u->pieces.empty()) node.fail("<union> needs at least one piece");
    piece = u;
  } else if (tag == "intersection") {
    auto u = std::make_shared<IntersectionPiece>();
    u->pieces = childPieces(node);
    if (u->pieces.empty()) node.fail("<intersection> needs at least one piece");
    piece = u;
  } else if (tag == "difference") {
    auto d = std::make_shared<DifferencePiece>();
    auto parts = childPieces(node);
    if (parts.size() != 2) node.fail("<difference> needs exactly two pieces (first minus second)");
    d->first = parts[0];
    d->second = parts[1];
    piece = d;
  } else if (tag == "smoothcyl") {
    piece = SmoothCylinderPiece::fromInput(node);
  } else if (isPieceTag(tag)) {
    node.fail("geometry piece <" + tag +
              "> is not supported; accepted: box, cylinder, sphere, "
              "smoothcyl, union, intersection, difference");
  } else {
    node.fail("<" + tag + "> is not a geometry piece");
  }
  if (label) labelled_[*label] = piece;
  return piece;
}

}  // namespace anode
