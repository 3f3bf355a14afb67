#include "Core/Geometry/SmoothCylinder.h"

#include <cmath>

namespace anode {

std::shared_ptr<SmoothCylinderPiece> SmoothCylinderPiece::fromInput(const PSNode& node) {
  auto c = std::make_shared<SmoothCylinderPiece>();
  const std::string scheme = node.require<std::string>("discretization_scheme");
  if (scheme == "pie_slices")
    c->scheme = Scheme::PieSlices;
  else if (scheme == "constant_particle_volumes")
    c->scheme = Scheme::ConstantParticleVolumes;
  else
    node.requireChild("discretization_scheme")
        .fail("<discretization_scheme> must be pie_slices or constant_particle_volumes, found \"" +
              scheme + "\"");
  c->bottom = node.require<Vec3>("bottom");
  c->top = node.require<Vec3>("top");
  if ((c->top - c->bottom).norm() == 0) node.requireChild("top").fail("<top> equals <bottom>");
  c->outerRadius = node.require<double>("outer_radius");
  if (!(c->outerRadius > 0))
    node.requireChild("outer_radius").fail("<outer_radius> must be positive");
  c->innerRadius = node.get<double>("inner_radius", 0.0);
  if (c->innerRadius < 0 || c->innerRadius >= c->outerRadius)
    node.requireChild("inner_radius").fail("<inner_radius> must lie in [0, outer_radius)");
  c->numRadial = node.require<int>("num_radial");
  if (c->numRadial < 1) node.requireChild("num_radial").fail("<num_radial> must be >= 1");
  c->numAxial = node.require<int>("num_axial");
  if (c->numAxial < 1) node.requireChild("num_axial").fail("<num_axial> must be >= 1");
  if (c->scheme == Scheme::PieSlices) {
    c->numAngular = node.require<int>("num_angular");
    if (c->numAngular < 1) node.requireChild("num_angular").fail("<num_angular> must be >= 1");
  } else {
    node.acceptInert("num_angular");  // constant_particle_volumes chooses its own
  }
  const double start = node.get<double>("arc_start_angle", 0.0);
  const double angle = node.get<double>("arc_angle", 360.0);
  if (start < 0 || start > 360)
    node.requireChild("arc_start_angle").fail("<arc_start_angle> must lie in [0, 360]");
  if (!(angle > 0) || angle > 360)
    node.requireChild("arc_angle").fail("<arc_angle> must lie in (0, 360]");
  c->arcStart = start * M_PI / 180;
  c->arcAngle = angle * M_PI / 180;
  if (c->arcAngle <= c->arcStart)
    node.requireChild("arc_angle")
        .fail(
            "<arc_angle> must exceed <arc_start_angle> (Uintah spans arc_angle - arc_start_angle)");
  if (const PSNode cap = node.child("endcap_thickness"))
    if (cap.value<double>() > 0) cap.unsupported("smoothcyl end caps <endcap_thickness>");
  node.acceptInert("output_file");
  return c;
}

bool SmoothCylinderPiece::inside(const Vec3& x) const {
  const Vec3 axis = top - bottom;
  const double along = (x - bottom).dot(axis);
  if (along < 0 || along > axis.squaredNorm()) return false;
  const double r2 = (x - bottom).cross(axis).squaredNorm() / axis.squaredNorm();
  return r2 <= outerRadius * outerRadius && r2 > innerRadius * innerRadius;
}

double SmoothCylinderPiece::slicesInRing(int ii, double cellVolume) const {
  const double dz = (top - bottom).norm() / numAxial, dr = (outerRadius - innerRadius) / numRadial;
  const double rIn = innerRadius + ii * dr, rOut = rIn + dr, r = rIn + 0.5 * dr;
  // Uintah spans arc_angle - arc_start_angle, starting at arc_start_angle.
  const double span = arcAngle - arcStart;
  if (scheme == Scheme::ConstantParticleVolumes) return std::max(1.0, std::floor(span * r / dr));
  // Fewer slices (x0.9 steps) until a slice holds at least 5% of a cell.
  double reduction = 1;
  int n = std::max(1, static_cast<int>(numAngular * reduction));
  while (0.5 * span / n * (rOut * rOut - rIn * rIn) * dz < 0.05 * cellVolume && n > 1) {
    reduction *= 0.9;
    n = std::max(1, static_cast<int>(numAngular * reduction));
  }
  return n;
}

double SmoothCylinderPiece::particleCount(const Grid& grid, double limit) const {
  // Every ring holds at least one particle.
  if (static_cast<double>(numRadial) * numAxial > limit)
    return static_cast<double>(numRadial) * numAxial;
  double perLayer = 0;
  for (int ii = 0; ii < numRadial && perLayer * numAxial <= limit; ++ii)
    perLayer += slicesInRing(ii, grid.dx.prod());
  return perLayer * numAxial;
}

std::vector<SmoothParticle> SmoothCylinderPiece::createParticles(const Grid& grid) const {
  const Vec3 axisVector = top - bottom;
  const double length = axisVector.norm();
  const Vec3 axis = axisVector / length;
  // Rings are laid out around z and rotated onto the cylinder's axis.
  const Mat3 R = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), axis).toRotationMatrix();
  const double dz = length / numAxial, dr = (outerRadius - innerRadius) / numRadial;
  const double span = arcAngle - arcStart;
  const double cellVolume = grid.dx.prod();
  std::vector<SmoothParticle> out;
  for (int kk = 0; kk < numAxial; ++kk) {
    const Vec3 center = bottom + axis * ((kk + 0.5) * dz);
    for (int ii = 0; ii < numRadial; ++ii) {
      const double rIn = innerRadius + ii * dr, rOut = rIn + dr, r = rIn + 0.5 * dr;
      const int n = static_cast<int>(slicesInRing(ii, cellVolume));
      const double dtheta = span / n;
      const double sliceArea = 0.5 * dtheta * (rOut * rOut - rIn * rIn);
      for (int jj = 0; jj < n; ++jj) {
        const double phi = arcStart + (jj + 0.5) * dtheta;
        const Vec3 radial(std::cos(phi), std::sin(phi), 0);
        const Vec3 tangential(std::sin(phi), -std::cos(phi), 0);
        // Physical edge vectors (chord, thickness, length), rotated onto the axis, in cell units.
        Mat3 edges;
        edges.col(0) = r * dtheta * tangential;
        edges.col(1) = dr * radial;
        edges.col(2) = Vec3(0, 0, dz);
        SmoothParticle p;
        p.x = center + R * (r * radial);
        p.volume = sliceArea * dz;
        p.size = grid.dx.cwiseInverse().asDiagonal() * (R * edges);
        // The outer face (radius rOut) is the one a side flux enters through.
        p.faceArea = Vec3(dz * rOut * dtheta, dz * rOut * dtheta, sliceArea);
        out.push_back(p);
      }
    }
  }
  return out;
}

}  // namespace anode
