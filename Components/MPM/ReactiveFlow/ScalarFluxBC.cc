#include "Components/MPM/ReactiveFlow/ScalarFluxBC.h"

#include <cmath>
#include <sstream>
#include <string>

namespace anode {

namespace {

// An optional <tag> of `block` naming one of two rules: true for `other`, false for `usual` (the
// default); anything else is an error at the tag listing both with what they mean.
bool readRule(const PSNode& block, const char* tag, const std::string& usual,
              const std::string& usualMeaning, const std::string& other,
              const std::string& otherMeaning) {
  const PSNode node = block.child(tag);
  if (!node) return false;
  const std::string value = node.value<std::string>();
  if (value != usual && value != other)
    node.fail("<" + std::string(tag) + "> must be " + usual + " (" + usualMeaning + ") or " +
              other + " (" + otherMeaning + "), found \"" + value + "\"");
  return value == other;
}

void readGeometry(const PSNode& geom, ScalarFluxBC& bc) {
  using Face = ScalarFluxBC::Face;
  bc.geomLine = geom.line();
  const auto pieces = geom.children();
  if (pieces.size() != 1)
    geom.fail("a <scalar_flux> <geom_object> holds exactly one box, cylinder or sphere");
  const PSNode piece = pieces[0];
  const std::string type = piece.name();
  if (type == "box") {
    bc.face = Face::Box;
    bc.boxMin = piece.require<Vec3>("min");
    bc.boxMax = piece.require<Vec3>("max");
    if ((bc.boxMax.array() < bc.boxMin.array()).any())
      piece.requireChild("max").fail("<max> must be >= <min>");
  } else if (type == "cylinder") {
    bc.bottom = piece.require<Vec3>("bottom");
    bc.top = piece.require<Vec3>("top");
    bc.radius = piece.require<double>("radius");
    if (!(bc.radius > 0)) piece.requireChild("radius").fail("<radius> must be positive");
    if ((bc.top - bc.bottom).norm() == 0) piece.requireChild("top").fail("<top> equals <bottom>");
    bc.face = piece.get<bool>("cylinder_end", false) ? Face::CylinderEnd : Face::CylinderSide;
    if (const PSNode a = piece.child("axisymmetric_end"))
      if (a.value<bool>()) a.unsupported("axisymmetric flux boundary conditions");
    if (const PSNode a = piece.child("axisymmetric_side"))
      if (a.value<bool>()) a.unsupported("axisymmetric flux boundary conditions");
  } else if (type == "sphere") {
    bc.face = Face::Sphere;
    const PSNode origin = piece.child("origin");
    bc.center = origin ? origin.value<Vec3>() : piece.require<Vec3>("center");
    bc.radius = piece.require<double>("radius");
    if (!(bc.radius > 0)) piece.requireChild("radius").fail("<radius> must be positive");
  } else {
    piece.fail("a <scalar_flux> geometry must be a box, cylinder or sphere, found <" + type + ">");
  }
}

// <surface material="NAME" exclude="NAME1 NAME2"/>: the material's free surface.
void readSurface(const PSNode& surface, ScalarFluxBC& bc) {
  bc.face = ScalarFluxBC::Face::Surface;
  bc.geomLine = surface.line();
  for (const std::string& a : surface.attributeNames())
    if (a != "material" && a != "exclude")
      surface.fail("<surface> takes the attributes material and exclude, found " + a);
  bc.surfaceMaterial = surface.requireAttribute("material");
  std::istringstream names(surface.attribute("exclude").value_or(""));
  for (std::string name; names >> name;) bc.excluded.push_back(name);
  if (!surface.children().empty())
    surface.fail("<surface> has no content: its attributes name the material (and exclude)");
}

}  // namespace

bool onSurface(const GeometryPiece& piece, const Vec3& x, const Vec3& dxp, int ndim) {
  const int dims = ndim == 3 ? 3 : 2;
  for (int k = 0; k < dims; ++k) {
    Vec3 step = Vec3::Zero();
    step[k] = dxp[k];
    if (!piece.inside(x + step) || !piece.inside(x - step)) return true;
  }
  return false;
}

namespace {

// <surface_reaction> (SurfaceReaction.h): every value checked, each error on its line.
std::shared_ptr<const SurfaceReaction> readSurfaceReaction(const PSNode& node) {
  auto r = std::make_shared<SurfaceReaction>();
  const auto positive = [&](const char* tag) {
    const double v = node.require<double>(tag);
    if (!(v > 0 && std::isfinite(v)))
      node.requireChild(tag).fail("<" + std::string(tag) + "> must be above 0");
    return v;
  };
  r->temperature = positive("temperature");
  r->exchangeFlux = positive("exchange_flux");
  r->openCircuitPotential = node.require<double>("open_circuit_potential");
  if (!std::isfinite(r->openCircuitPotential))
    node.requireChild("open_circuit_potential").fail("<open_circuit_potential> must be finite");
  if (const PSNode alpha = node.child("transfer_coefficient")) {
    r->transferCoefficient = alpha.value<double>();
    if (!(r->transferCoefficient > 0 && r->transferCoefficient < 1))
      alpha.fail("<transfer_coefficient> must lie in (0, 1)");
  }
  for (auto [tag, value] : {std::pair{"lower_cutoff_potential", &r->lowerCutoff},
                            std::pair{"upper_cutoff_potential", &r->upperCutoff}})
    if (const PSNode cutoff = node.child(tag)) {
      *value = cutoff.value<double>();
      if (!std::isfinite(*value)) cutoff.fail("<" + std::string(tag) + "> must be finite");
    }
  if (!(r->lowerCutoff < r->upperCutoff))
    node.requireChild("upper_cutoff_potential")
        .fail("<upper_cutoff_potential> must lie above <lower_cutoff_potential>");
  node.requireEverythingRead();
  return r;
}

}  // namespace

std::vector<ScalarFluxBC> ScalarFluxBC::fromInput(const std::vector<PSNode>& blocks) {
  std::vector<ScalarFluxBC> out;
  for (const PSNode& block : blocks) {
    ScalarFluxBC bc;
    bc.line = block.line();
    if (const PSNode surface = block.child("surface")) {
      if (block.child("geom_object"))
        surface.fail("a <scalar_flux> takes a <geom_object> or a <surface>, not both");
      readSurface(surface, bc);
    } else {
      readGeometry(block.requireChild("geom_object"), bc);
    }
    bc.deformedArea = readRule(block, "area_update", "constant", "Uintah's fixed face area",
                               "deformed", "Nanson");
    if (bc.deformedArea && bc.face == Face::Surface)
      block.requireChild("area_update")
          .fail("<area_update>deformed needs a BC geometry's normal; a <surface> BC has none");
    bc.particleFaceArea = readRule(block, "area_rule", "surface",
                                   "the area of the BC surface, shared among the flagged particles",
                                   "particle_face", "Uintah's face of each particle");
    if (const PSNode mode = block.child("mode")) {
      const std::string value = mode.value<std::string>();
      if (value == "galvanostatic")
        bc.mode = Mode::Galvanostatic;
      else if (value == "potentiostatic")
        bc.mode = Mode::Potentiostatic;
      else if (value != "flux")
        mode.fail(
            "<mode> must be flux (the load is the flux J through the surface, Eq. 16), "
            "galvanostatic (the load is the total lithium rate into the flagged particles) or "
            "potentiostatic (the load is the surface concentration held), found \"" +
            value + "\"");
    }
    if (const PSNode rate = block.child("surface_rate")) {
      if (bc.mode != Mode::Potentiostatic)
        rate.fail("<surface_rate> belongs to <mode>potentiostatic</mode>");
      bc.surfaceRate = rate.value<double>();
      if (!(bc.surfaceRate > 0 && std::isfinite(bc.surfaceRate)))
        rate.fail("<surface_rate> must be above 0");
    } else if (bc.mode == Mode::Potentiostatic) {
      block.requireChild("mode").fail(
          "<mode>potentiostatic</mode> needs <surface_rate>, the rate constant k of the surface "
          "reaction (length per time): the flux is k (c_s - c)");
    }
    if (const PSNode cutoff = block.child("cutoff")) {
      if (bc.mode != Mode::Galvanostatic)
        cutoff.fail("<cutoff> belongs to <mode>galvanostatic</mode>");
      bc.cutoff = cutoff.value<double>();
      if (!(bc.cutoff > 0 && bc.cutoff < 1))
        cutoff.fail(
            "<cutoff> (the flagged surface's mean restriction R at which the current "
            "ends) must lie in (0, 1)");
    }
    if (const PSNode unit = block.child("rate_unit")) {
      if (bc.mode != Mode::Galvanostatic)
        unit.fail("<rate_unit> belongs to <mode>galvanostatic</mode>");
      const std::string value = unit.value<std::string>();
      if (value == "C") {
        const PSNode hour = block.child("hour");
        if (!hour)
          unit.fail(
              "<rate_unit>C</rate_unit> needs <hour>, an hour in the input's time unit (3.6e9 "
              "for microseconds)");
        bc.hour = hour.value<double>();
        if (!(bc.hour > 0 && std::isfinite(bc.hour))) hour.fail("<hour> must be above 0");
      } else if (value != "lithium_per_time") {
        unit.fail(
            "<rate_unit> must be lithium_per_time (default: the load is the lithium rate, sum m c "
            "per time) or C (the load is a C-rate), found \"" +
            value + "\"");
      }
    }
    if (bc.hour == 0)
      if (const PSNode hour = block.child("hour"))
        hour.fail("<hour> belongs to <rate_unit>C</rate_unit>");
    if (const PSNode reaction = block.child("surface_reaction")) {
      if (bc.mode != Mode::Galvanostatic)
        reaction.fail("<surface_reaction> belongs to <mode>galvanostatic</mode>");
      if (const PSNode cutoff = block.child("cutoff"))
        cutoff.fail(
            "<cutoff> (the surface's mean restriction) does not go with <surface_reaction>, "
            "whose cutoffs are potentials: <lower_cutoff_potential>, <upper_cutoff_potential>");
      bc.reaction = readSurfaceReaction(reaction);
    }
    block.acceptInert("outward_normal");
    block.acceptInert("auto_cycle");
    block.acceptInert("numberOfParticlesOnLoadSurface");
    const PSNode curve = block.requireChild("load_curve");
    const int id = curve.require<int>("id");
    // Uintah looks up the BC of a particle by id - 1 in file order (UINTAH_UPS.md P16).
    if (id != static_cast<int>(out.size()) + 1)
      curve.requireChild("id").fail("load curve <id> must be " + std::to_string(out.size() + 1) +
                                    ": ids number the <scalar_flux> blocks 1..N in file order");
    bc.load = LoadCurve::fromInput(curve);
    // A misspelt tag (<cylinder_ends>) is reported as such, before setup finds that the
    // geometry, read without it, flags no particle.
    block.requireEverythingRead();
    out.push_back(std::move(bc));
  }
  return out;
}

Vec3 ScalarFluxBC::normalAt(const Vec3& x) const {
  switch (face) {
    case Face::Box: {
      int axis = 0;
      (boxMax - boxMin).minCoeff(&axis);
      return Vec3::Unit(axis);
    }
    case Face::CylinderSide: {
      const Vec3 axis = (top - bottom).normalized();
      const Vec3 radial = (x - bottom) - (x - bottom).dot(axis) * axis;
      return radial.norm() > 0 ? Vec3(radial.normalized()) : Vec3::UnitX();
    }
    case Face::CylinderEnd:
      return (top - bottom).normalized();
    case Face::Sphere:
      return (x - center).norm() > 0 ? Vec3((x - center).normalized()) : Vec3::UnitX();
    case Face::Surface:
      break;  // no geometry of its own: not with splitting or <area_update>deformed
  }
  return Vec3::UnitX();
}

double ScalarFluxBC::areaStretch(const Mat3& F, const Vec3& X) const {
  // Nanson: a n = J F^-T A N, so |a| / A = J |F^-T N| with N the face normal at X.
  return F.determinant() * (F.inverse().transpose() * normalAt(X)).norm();
}

double ScalarFluxBC::distanceToFace(const Vec3& x) const {
  switch (face) {
    case Face::Box:
      return std::abs((x - 0.5 * (boxMin + boxMax)).dot(normalAt(x)));
    case Face::CylinderSide: {
      const Vec3 axis = (top - bottom).normalized();
      return std::abs(((x - bottom) - (x - bottom).dot(axis) * axis).norm() - radius);
    }
    case Face::CylinderEnd: {
      const Vec3 axis = (top - bottom).normalized();
      const double along = (x - bottom).dot(axis);
      return std::min(std::abs(along), std::abs(along - (top - bottom).norm()));
    }
    case Face::Sphere:
      return std::abs((x - center).norm() - radius);
    case Face::Surface:
      break;
  }
  return 0;
}

double ScalarFluxBC::flaggedArea(const Vec3& x, const Vec3& dxp, const Vec3& faceAreas) const {
  switch (face) {
    case Face::Box: {
      if ((x.array() < (boxMin - dxp).array()).any() || (x.array() > (boxMax + dxp).array()).any())
        return 0;
      // The BC's normal is the axis of the box's smallest extent.
      int axis = 0;
      (boxMax - boxMin).minCoeff(&axis);
      return faceAreas[axis];
    }
    case Face::CylinderSide:
    case Face::CylinderEnd: {
      const double tol = 0.9 * dxp.minCoeff();
      const Vec3 axis = (top - bottom).normalized();
      const double length = (top - bottom).norm();
      const double along = (x - bottom).dot(axis);
      const Vec3 radial = (x - bottom) - along * axis;
      if (face == Face::CylinderSide) {
        if (along < 0 || along > length) return 0;
        const double r = radial.norm();
        if (r < radius - tol || r > radius + tol) return 0;
        // Projection of the particle's faces onto the radial direction (in-plane normal).
        const Vec3 n = radial / r;
        return std::sqrt(std::pow(faceAreas.x() * n.x(), 2) + std::pow(faceAreas.y() * n.y(), 2) +
                         std::pow(faceAreas.z() * n.z(), 2));
      }
      if (along < -tol || along > length + tol || radial.norm() > radius) return 0;
      return std::sqrt(std::pow(faceAreas.x() * axis.x(), 2) +
                       std::pow(faceAreas.y() * axis.y(), 2) +
                       std::pow(faceAreas.z() * axis.z(), 2));
    }
    case Face::Sphere: {
      const double r = (x - center).norm();
      if (std::abs(r - radius) > dxp.norm()) return 0;
      return faceAreas.x();
    }
    case Face::Surface:
      break;  // flagged by material (ExternalScalarFlux::assignToParticles)
  }
  return 0;
}

}  // namespace anode
