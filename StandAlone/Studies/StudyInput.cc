#include "StandAlone/Studies/StudyInput.h"

#include <cstdio>
#include <stdexcept>

namespace anode {

void requireInterpolator(const std::string& problem, const std::string& interpolator) {
  if (interpolator != "linear" && interpolator != "gimp" && interpolator != "cpdi")
    throw std::invalid_argument(problem + ": interpolator must be linear, gimp or cpdi");
}

std::string upsOpening(const std::string& comment, const std::string& title,
                       const std::string& component) {
  std::string s;
  s += "<?xml version=\"1.0\" encoding=\"iso-8859-1\"?>\n";
  s += "<!-- " + comment + " -->\n";
  s += "<Uintah_specification>\n";
  s += "  <Meta><title>" + title + "</title></Meta>\n";
  s += "  <SimulationComponent type=\"" + component + "\"/>\n";
  return s;
}

std::string upsTimeAndArchiver(double endTime, double maxDt, double multiplier,
                               const std::string& filebase, double firstDt) {
  std::string s;
  s += "  <Time>\n";
  s += "    <initTime>0</initTime>\n";
  s += "    <maxTime>" + upsNumber(endTime) + "</maxTime>\n";
  s += "    <delt_min>0</delt_min>\n";
  s += "    <delt_max>" + upsNumber(maxDt) + "</delt_max>\n";
  if (firstDt > 0) s += "    <delt_init>" + upsNumber(firstDt) + "</delt_init>\n";
  s += "    <timestep_multiplier>" + upsNumber(multiplier) + "</timestep_multiplier>\n";
  s += "    <end_at_max_time_exactly>true</end_at_max_time_exactly>\n";
  s += "  </Time>\n";
  s += "  <DataArchiver>\n";
  s += "    <filebase>" + filebase + "</filebase>\n";
  s += "    <outputTimestepInterval>100000000</outputTimestepInterval>\n";
  s += "  </DataArchiver>\n";
  return s;
}

std::string upsMPM(const std::string& interpolator, const std::string& options,
                   const std::string& integrator) {
  std::string s;
  s += "  <MPM>\n";
  s += "    <time_integrator>" + integrator + "</time_integrator>\n";
  s += "    <interpolator>" + interpolator + "</interpolator>\n";
  s += options;
  s += "  </MPM>\n";
  return s;
}

std::string upsMaterialProperties(const std::string& material, const std::string& more,
                                  const std::string& gravity) {
  const std::string opening = "  <PhysicalConstants><gravity>" + gravity +
                              "</gravity></PhysicalConstants>\n"
                              "  <MaterialProperties>\n"
                              "    <MPM>\n";
  const std::string closing =
      "    </MPM>\n"
      "  </MaterialProperties>\n";
  return opening + material + "      <contact><type>null</type></contact>\n" + more + closing;
}

std::string upsElasticModel(double bulkModulus, double shearModulus, bool diffuses) {
  std::string s;
  s += "        <constitutive_model type=\"rf_elastic_plastic\">\n";
  s += "          <bulk_modulus>" + upsNumber(bulkModulus) + "</bulk_modulus>\n";
  s += "          <shear_modulus>" + upsNumber(shearModulus) + "</shear_modulus>\n";
  if (diffuses) s += "          <volume_expansion_coeff>0</volume_expansion_coeff>\n";
  s += "          <equation_of_state type=\"default_hypo\"/>\n";
  s += "        </constitutive_model>\n";
  return s;
}

std::string upsParticleBox(const std::string& label, double length, double width,
                           double temperature, bool diffuses) {
  std::string s;
  s += "        <geom_object>\n";
  s += "          <box label=\"" + label + "\"><min>[0,0,0]</min><max>" +
       upsVector(length, width, width) + "</max></box>\n";
  s += "          <res>[2,1,1]</res>\n";
  s += "          <velocity>[0,0,0]</velocity>\n";
  s += "          <temperature>" + upsNumber(temperature) + "</temperature>\n";
  if (diffuses) s += "          <concentration>0</concentration>\n";
  s += "        </geom_object>\n";
  return s;
}

std::string upsSymmetricFace(const std::string& side) {
  return "      <Face side=\"" + side +
         "\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>\n";
}

std::string upsGrid(const std::string& faces, double length, double width, int cellsAlong,
                    int cellsAcross, const std::string& extraCells) {
  const std::string across = std::to_string(cellsAcross);
  std::string s;
  s += "  <Grid>\n";
  s += "    <BoundaryConditions>\n";
  s += faces;
  s += "    </BoundaryConditions>\n";
  s += "    <Level>\n";
  s += "      <Box label=\"1\">\n";
  s += "        <lower>[0,0,0]</lower>\n";
  s += "        <upper>" + upsVector(length, width, width) + "</upper>\n";
  s += "        <resolution>[" + std::to_string(cellsAlong) + "," + across + "," + across +
       "]</resolution>\n";
  s += "        <extraCells>" + extraCells + "</extraCells>\n";
  s += "        <patches>[1,1,1]</patches>\n";
  s += "      </Box>\n";
  s += "    </Level>\n";
  s += "  </Grid>\n";
  return s;
}

std::string upsSphereOctantGrid(double radius, int cells, const std::string& interpolator) {
  const int gridCells = cells + 2;
  const double side = gridCells * radius / cells;
  std::string faces;
  for (const char* face : {"x-", "y-", "z-"}) faces += upsSymmetricFace(face);
  return upsGrid(faces, side, side, gridCells, gridCells,
                 interpolator == "linear" ? "[0,0,0]" : "[1,1,1]");
}

}  // namespace anode
