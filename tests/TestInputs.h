// Small inputs built in memory for tests: one elastic(-plastic) block on a box grid.
#pragma once

#include <sstream>
#include <string>

namespace anode::testing {

struct BlockInput {
  std::string interpolator = "linear";
  std::string boxMin = "[0.25, 0.25, 0.25]", boxMax = "[0.75, 0.75, 0.75]";
  std::string res = "[2,2,2]";
  std::string velocity = "[0,0,0]";
  std::string gridLower = "[0,0,0]", gridUpper = "[1,1,1]", cells = "[10,10,10]";
  std::string extraCells = "[1,1,1]";
  std::string flowModel;  // empty: linear elastic
  std::string faces;      // <Face> elements
  std::string saves = "<save label=\"p.stress\"/>";
  std::string extraMaterials;  // further <material> elements
  std::string contact;         // <contact> element
  std::string mpmFlags;        // further <MPM> flags
  std::string amr;             // an <AMR> element
  double maxTime = 1.0, multiplier = 0.2;
  int maxSteps = 10;
  int outputEvery = 1;
  double density = 1000, bulk = 1e6, shear = 5e5;

  std::string text() const {
    std::ostringstream s;
    s << "<?xml version='1.0'?>\n<Uintah_specification>\n"
      << "<SimulationComponent type=\"mpm\"/>\n"
      << "<Time><maxTime>" << maxTime << "</maxTime><initTime>0</initTime>"
      << "<delt_min>0</delt_min><delt_max>1</delt_max><timestep_multiplier>" << multiplier
      << "</timestep_multiplier><max_Timesteps>" << maxSteps << "</max_Timesteps></Time>\n"
      << "<DataArchiver><filebase>test.uda</filebase><outputTimestepInterval>" << outputEvery
      << "</outputTimestepInterval>" << saves << "</DataArchiver>\n"
      << "<MPM><interpolator>" << interpolator << "</interpolator>" << mpmFlags << "</MPM>\n"
      << amr << "<MaterialProperties><MPM><material name=\"block\"><density>" << density
      << "</density>"
      << "<constitutive_model type=\"rf_elastic_plastic\"><bulk_modulus>" << bulk
      << "</bulk_modulus><shear_modulus>" << shear << "</shear_modulus>"
      << "<equation_of_state type=\"default_hypo\"/>" << flowModel << "</constitutive_model>"
      << "<geom_object><box label=\"b\"><min>" << boxMin << "</min><max>" << boxMax
      << "</max></box><res>" << res << "</res><velocity>" << velocity
      << "</velocity><temperature>298</temperature></geom_object></material>" << extraMaterials
      << contact << "</MPM></MaterialProperties>\n"
      << "<Grid><Level><Box><lower>" << gridLower << "</lower><upper>" << gridUpper
      << "</upper><resolution>" << cells << "</resolution><extraCells>" << extraCells
      << "</extraCells></Box></Level><BoundaryConditions>" << faces
      << "</BoundaryConditions></Grid>\n"
      << "</Uintah_specification>\n";
    return s.str();
  }
};

}  // namespace anode::testing
