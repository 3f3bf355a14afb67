// Pins the output layout (DESIGN.md §6): VTU files that VTK's XML reader opens with the saved
// labels and the right values, a .pvd listing every output, grid files only for g.* labels,
// history.csv and a copy of the input.
#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "Core/ProblemSpec/ProblemSpec.h"
#include "StandAlone/Driver/DataArchiver.h"
#include "StandAlone/Driver/OutputLabels.h"
#include "StandAlone/Driver/Simulation.h"
#include "TestFiles.h"
#include "TestInputs.h"

namespace fs = std::filesystem;

namespace anode {
namespace {

using testing::readFile;

struct OutputRun {
  fs::path dir;
  explicit OutputRun(const testing::BlockInput& in, const std::string& name) {
    dir = fs::temp_directory_path() / ("anode_output_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const fs::path input = dir.string() + ".ups";
    std::ofstream(input) << in.text();
    const std::string cmd =
        std::string(ANODE_SUS) + " -o " + dir.string() + " " + input.string() + " 2>/dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  ~OutputRun() {
    fs::remove_all(dir);
    fs::remove(dir.string() + ".ups");
  }
};

testing::BlockInput allLabels() {
  testing::BlockInput in;
  in.interpolator = "cpdi";
  in.velocity = "[1, 2, 3]";
  in.maxSteps = 5;
  in.outputEvery = 2;
  in.flowModel =
      "<flow_model type=\"johnson_cook\"><A>1e4</A><B>0</B><C>0</C><n>0</n><m>1</m></flow_model>"
      "<yield_condition type=\"vonMises\"/>";
  in.saves =
      "<save label=\"p.x\"/><save label=\"p.stress\"/><save label=\"p.deformationMeasure\"/>"
      "<save label=\"p.particleID\"/><save label=\"p.mass\"/><save label=\"p.volume\"/>"
      "<save label=\"p.velocity\"/><save label=\"p.displacement\"/><save "
      "label=\"p.plasticStrain\"/>";
  return in;
}

// <DataArchiver> intervals: optional, 0 (Uintah's default) or absent means no periodic output.
TEST(DataArchiver, OutputIntervalsAreOptionalAsInUintah) {
  const auto outputsAt = [](const std::string& tags, long step, double time) {
    const auto spec = ProblemSpec::fromText(
        "<Uintah_specification><DataArchiver>" + tags + "</DataArchiver></Uintah_specification>",
        "archiver.ups");
    return DataArchiver::fromInput(spec->root().requireChild("DataArchiver"), false, 1)
        .isOutputStep(step, time);
  };
  EXPECT_FALSE(outputsAt("", 5, 1e9));
  EXPECT_FALSE(outputsAt("<outputInterval>0</outputInterval>", 5, 1e9));
  EXPECT_FALSE(outputsAt("<outputTimestepInterval>0</outputTimestepInterval>", 5, 1e9));
  EXPECT_TRUE(outputsAt("<outputTimestepInterval>5</outputTimestepInterval>", 5, 0));
  EXPECT_TRUE(outputsAt("<outputInterval>0.5</outputInterval>", 1, 0.5));
  // Uintah rejects the pair only when both are above 0.
  EXPECT_TRUE(outputsAt(
      "<outputInterval>0</outputInterval><outputTimestepInterval>5</outputTimestepInterval>", 5,
      0));
}

// <save material= levels=>: Uintah's index sets. A set naming every material of the one level
// asks for what is written anyway; a set leaving one out is unsupported, not silently widened.
TEST(DataArchiver, SaveForEveryMaterialOrTheOneLevelIsAccepted) {
  const auto read = [](const std::string& attributes, int numMaterials) {
    const auto spec = ProblemSpec::fromText(
        "<Uintah_specification><DataArchiver><filebase>a.uda</filebase>"
        "<save label=\"p.x\" " +
            attributes + "/></DataArchiver></Uintah_specification>",
        "archiver.ups");
    DataArchiver::fromInput(spec->root().requireChild("DataArchiver"), false, numMaterials);
  };
  EXPECT_NO_THROW(read("material=\"0\"", 1));
  EXPECT_NO_THROW(read("material=\"0-1\"", 2));
  EXPECT_NO_THROW(read("material=\"1, 0\"", 2));
  EXPECT_NO_THROW(read("material=\"0 1\"", 2));
  EXPECT_NO_THROW(read("material=\"\"", 2));
  EXPECT_NO_THROW(read("material=\" 0, 1, \"", 2));
  EXPECT_NO_THROW(read("levels=\"0\"", 1));
  EXPECT_NO_THROW(read("levels=\"-3--1\"", 1));
  EXPECT_THROW(read("material=\"0\"", 2), InputError);
  EXPECT_THROW(read("material=\"1-2\"", 2), InputError);
  EXPECT_THROW(read("levels=\"1\"", 1), InputError);
  EXPECT_THROW(read("material=\"0-\"", 1), InputError);
  EXPECT_THROW(read("material=\"0;1\"", 2), InputError);
}

TEST(Output, VtuFilesCarryTheSavedLabels) {
  const testing::BlockInput in = allLabels();
  OutputRun run(in, "labels");
  const std::string pvd = readFile(run.dir / "particles.pvd");
  // Steps 0, 2, 4 by the interval and 5 as the last step.
  std::vector<std::string> files;
  std::regex entry("file=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), entry); it != std::sregex_iterator();
       ++it)
    files.push_back((*it)[1]);
  ASSERT_EQ(files.size(), 4u) << pvd;
  EXPECT_EQ(files.front(), "particles/step_000000.vtu");
  EXPECT_EQ(files.back(), "particles/step_000005.vtu");

  for (const std::string& f : files) {
    auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    reader->SetFileName((run.dir / f).c_str());
    reader->Update();
    vtkUnstructuredGrid* ug = reader->GetOutput();
    ASSERT_EQ(ug->GetNumberOfPoints(), 5 * 5 * 5 * 8) << f;  // 0.5^3 block, dx 0.1, res 2
    EXPECT_EQ(ug->GetNumberOfCells(), ug->GetNumberOfPoints());
    vtkPointData* pd = ug->GetPointData();
    for (const char* name : {"p.stress", "p.deformationMeasure"})
      ASSERT_TRUE(pd->GetArray(name) && pd->GetArray(name)->GetNumberOfComponents() == 9) << name;
    for (const char* name : {"p.velocity", "p.displacement"})
      ASSERT_TRUE(pd->GetArray(name) && pd->GetArray(name)->GetNumberOfComponents() == 3) << name;
    for (const char* name : {"p.particleID", "p.mass", "p.volume", "p.plasticStrain", "material"})
      ASSERT_TRUE(pd->GetArray(name) && pd->GetArray(name)->GetNumberOfComponents() == 1) << name;
  }

  // Values of the first particle in the first and last files.
  auto first = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
  first->SetFileName((run.dir / files.front()).c_str());
  first->Update();
  double x[3];
  first->GetOutput()->GetPoint(0, x);
  EXPECT_NEAR(x[0], 0.25 + 0.025, 1e-15);  // the first candidate of the first filled cell
  EXPECT_NEAR(x[1], 0.25 + 0.025, 1e-15);
  EXPECT_NEAR(x[2], 0.25 + 0.025, 1e-15);
  vtkPointData* pd = first->GetOutput()->GetPointData();
  EXPECT_NEAR(pd->GetArray("p.mass")->GetTuple1(0), in.density * std::pow(0.05, 3), 1e-15);
  EXPECT_NEAR(pd->GetArray("p.volume")->GetTuple1(0), std::pow(0.05, 3), 1e-18);
  EXPECT_EQ(pd->GetArray("p.particleID")->GetTuple1(0), 0);
  EXPECT_EQ(pd->GetArray("p.deformationMeasure")->GetComponent(0, 0), 1.0);
  EXPECT_EQ(pd->GetArray("p.velocity")->GetComponent(0, 2), 3.0);

  auto last = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
  last->SetFileName((run.dir / files.back()).c_str());
  last->Update();
  double xe[3];
  last->GetOutput()->GetPoint(0, xe);
  const double disp2 =
      last->GetOutput()->GetPointData()->GetArray("p.displacement")->GetComponent(0, 2);
  EXPECT_NEAR(xe[2] - x[2], disp2, 1e-14);
  EXPECT_GT(disp2, 0.0);

  // history.csv: a header and one row per step (0..5); the input copied alongside.
  const std::string history = readFile(run.dir / "history.csv");
  EXPECT_EQ(std::count(history.begin(), history.end(), '\n'), 7);
  EXPECT_EQ(history.rfind("step,time,dt,particles,kinetic_energy", 0), 0u);
  EXPECT_EQ(readFile(run.dir / "input.ups"), in.text());
  EXPECT_FALSE(fs::exists(run.dir / "grid.pvd")) << "no g.* label saved: no grid output";
  for (const auto& e : fs::recursive_directory_iterator(run.dir))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos)
        << "leftover temporary " << e.path();
}

TEST(Output, GridFilesOnlyForSavedGridLabels) {
  testing::BlockInput in;
  in.maxSteps = 2;
  in.saves = "<save label=\"g.mass\"/><save label=\"g.velocity\"/>";
  OutputRun run(in, "grid");
  ASSERT_TRUE(fs::exists(run.dir / "grid.pvd"));
  auto reader = vtkSmartPointer<vtkXMLImageDataReader>::New();
  reader->SetFileName((run.dir / "grid/step_000000.vti").c_str());
  reader->Update();
  vtkImageData* img = reader->GetOutput();
  EXPECT_EQ(img->GetNumberOfPoints(), 13 * 13 * 13);  // 10 cells + 1 + 2 extra per axis
  vtkDataArray* mass = img->GetPointData()->GetArray("g.mass");
  ASSERT_TRUE(mass);
  double total = 0;
  for (vtkIdType i = 0; i < mass->GetNumberOfTuples(); ++i) total += mass->GetTuple1(i);
  EXPECT_NEAR(total, in.density * 0.125, 1e-12) << "grid mass equals particle mass (Eq. 4)";
  EXPECT_TRUE(img->GetPointData()->GetArray("g.velocity"));
  EXPECT_FALSE(img->GetPointData()->GetArray("g.acceleration"));
}

TEST(Output, DiffusionGridLabelsNameTheirFields) {
  // A slab taking up lithium through x+ (no SD-Type BC): after the first step c_noBC = c, and
  // c* - c = (R + G)/m dt with R = 0 (c = 0 everywhere before the step) and G > 0 only on the
  // nodes the flux particles reach, while the nodal rate leaves G out (docs/diffusion.md).
  RunOptions quiet;
  quiet.progress = false;
  Simulation sim(readFile(std::string(ANODE_SOURCE_DIR) + "/tests/checkpoint/DiffCurveSlab.ups"),
                 "slab.ups", quiet);
  sim.advance();
  const GridData g = gatherGrid(sim.mpm(), {"g.concentration", "g.concentrationnobc",
                                            "g.concentrationStar", "g.concentrationRate"});
  ASSERT_EQ(g.arrays.size(), 4u);
  const std::vector<double>&c = g.arrays[0].real, &noBC = g.arrays[1].real,
        &star = g.arrays[2].real, &rate = g.arrays[3].real;
  int sourceNodes = 0;
  for (size_t k = 0; k < c.size(); ++k) {
    EXPECT_EQ(noBC[k], c[k]);
    EXPECT_EQ(rate[k], 0.0);
    EXPECT_GE(star[k], c[k]);
    if (star[k] > c[k]) ++sourceNodes;
  }
  EXPECT_GT(sourceNodes, 0);
}

TEST(Output, DefaultDirectoryIsVersionedWhenTaken) {
  const fs::path base = fs::temp_directory_path() / ("anode_base_" + std::to_string(::getpid()));
  fs::create_directories(base);
  EXPECT_EQ(chooseOutputDirectory("", base.string()), base.string() + ".000");
  EXPECT_EQ(chooseOutputDirectory("given", base.string()), "given");
  fs::remove_all(base);
}

}  // namespace
}  // namespace anode
