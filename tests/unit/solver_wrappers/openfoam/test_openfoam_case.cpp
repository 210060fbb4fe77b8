// Reading OpenFOAM dictionaries and checking a case for a coupled run, without OpenFOAM: the
// checks `cocopp check` makes before anything starts, and the `openfoam` wrapper's keys.
#include <gtest/gtest.h>

#include "solver_wrappers/openfoam/openfoam_case.hpp"
#include "solver_wrappers/process/process_solver_wrapper.hpp"
#include "tests/support/error_message.hpp"
#include "tests/support/temporary_directory.hpp"

using cocopp::testing::error_message;

namespace cocopp::openfoam {
namespace {

using testing::TemporaryDirectory;
using testing::write_text;

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "in: " << (text)

constexpr const char* kHeader =
    R"(/*--------------------------------*- C++ -*----------------------------------*\
| =========                 |                                                 |
\*---------------------------------------------------------------------------*/
FoamFile
{
    version     2.0;
    format      ascii;
    class       dictionary;
    object      controlDict;
}
)";

TEST(FoamDictionary, ReadsEntriesSubDictionariesListsAndComments) {
  TemporaryDirectory directory;
  write_text(directory / "dict", std::string(kHeader) + R"(
application     pimpleFoam;   // trailing comment
/* a block comment
   over lines; with { braces */
deltaT          1e-3;
functions
{
    forces { type forces; patches (wall); }
}
patches         (inlet "outlet" wall);
)");
  const auto dictionary = FoamDictionary::read(directory / "dict");
  EXPECT_EQ(dictionary.value("application"), "pimpleFoam");
  EXPECT_DOUBLE_EQ(dictionary.number("deltaT"), 1e-3);
  EXPECT_EQ(dictionary.where("deltaT"), (directory / "dict").string() + ":15");
  EXPECT_TRUE(dictionary.has("functions"));
  EXPECT_FALSE(dictionary.has("forces"));  // top level only
  EXPECT_EQ(dictionary.value("patches"), "( inlet \"outlet\" wall )");
  EXPECT_EQ(dictionary.value("endTime"), std::nullopt);
}

TEST(FoamDictionary, ErrorsNameTheFileAndLine) {
  TemporaryDirectory directory;
  const auto file = directory / "controlDict";
  EXPECT_CONTAINS(error_message<CaseError>([&] { FoamDictionary::read(file); }),
                  file.string() + ": cannot read");
  write_text(file, "deltaT abc;\n");
  EXPECT_CONTAINS(error_message<CaseError>([&] { FoamDictionary::read(file).number("deltaT"); }),
                  file.string() + ":1: 'deltaT' must be a number, not 'abc'");
  write_text(file, "a 1;\nfunctions\n{\n  x 2;\n");
  EXPECT_CONTAINS(error_message<CaseError>([&] { FoamDictionary::read(file); }),
                  file.string() + ":3: '{' is never closed");
  write_text(file, "a 1;\nendTime 2\n");
  EXPECT_CONTAINS(error_message<CaseError>([&] { FoamDictionary::read(file); }),
                  file.string() + ":2: entry 'endTime' does not end with ';'");
  write_text(file, "/* never closed\n");
  EXPECT_CONTAINS(error_message<CaseError>([&] { FoamDictionary::read(file); }),
                  "unterminated comment");
}

TEST(FoamBoundary, ListsThePatchesInOrder) {
  TemporaryDirectory directory;
  write_text(directory / "boundary", std::string(kHeader) + R"(
3
(
    inlet
    {
        type            patch;
        nFaces          6;
        startFace       214;
    }
    wall
    {
        type            wall;
        inGroups        List<word> 1(wall);
        nFaces          20;
        startFace       220;
    }
    frontAndBack
    {
        type            empty;
        nFaces          240;
        startFace       254;
    }
)
)");
  EXPECT_EQ(read_boundary_patches(directory / "boundary"),
            (std::vector<std::string>{"inlet", "wall", "frontAndBack"}));
}

/// A minimal case that passes every check; each test breaks one thing.
class CaseCheckTest : public ::testing::Test {
 protected:
  CaseCheckTest() {
    for (const char* sub : {"system", "constant/polyMesh"})
      std::filesystem::create_directories(directory_ / sub);
    write("system/controlDict", "deltaT 0.001;\nadjustTimeStep no;\n");
    write("constant/dynamicMeshDict",
          "dynamicFvMesh dynamicMotionSolverFvMesh;\nsolver displacementLaplacian;\n");
    write("constant/polyMesh/boundary", "2\n(\n inlet { type patch; }\n wall { type wall; }\n)\n");
    write("constant/transportProperties", "transportModel Newtonian;\nnu 1e-6;\nrho 1000;\n");
  }
  void write(const std::string& file, const std::string& body) {
    write_text(directory_ / file, std::string(kHeader) + body);
  }
  std::string file(const std::string& name) const { return (directory_ / name).string(); }
  CaseCheck check(double delta_t = 0.001) const {
    return {directory_.path(), {"wall"}, delta_t, "solver 'fluid': "};
  }

  TemporaryDirectory directory_;
};

TEST_F(CaseCheckTest, AcceptsACoupledCase) {
  EXPECT_NO_THROW(check().run());
}

TEST_F(CaseCheckTest, TheTimeStepMustBeTheCouplers) {
  EXPECT_CONTAINS(error_message<CaseError>([&] { check(0.002).run(); }),
                  file("system/controlDict") +
                      ":11: solver 'fluid': deltaT 0.001 differs from the coupler's time step "
                      "0.002 (delta_t, divided by the solver's substeps)");
  write("system/controlDict", "deltaT 0.001;\nadjustTimeStep yes;\n");
  EXPECT_CONTAINS(error_message<CaseError>([&] { check().run(); }),
                  file("system/controlDict") + ":12: solver 'fluid': adjustTimeStep yes");
  write("system/controlDict", "endTime 1;\n");
  EXPECT_CONTAINS(error_message<CaseError>([&] { check().run(); }),
                  file("system/controlDict") + ": the entry 'deltaT' is missing");
}

TEST_F(CaseCheckTest, TheMeshMustMoveWithAMotionSolver) {
  write("constant/dynamicMeshDict", "dynamicFvMesh staticFvMesh;\n");
  EXPECT_CONTAINS(
      error_message<CaseError>([&] { check().run(); }),
      file("constant/dynamicMeshDict") + ":11: solver 'fluid': dynamicFvMesh is staticFvMesh");
  std::filesystem::remove(directory_ / "constant/dynamicMeshDict");
  EXPECT_CONTAINS(error_message<CaseError>([&] { check().run(); }),
                  file("constant/dynamicMeshDict") + ": cannot read the file");
}

TEST_F(CaseCheckTest, TheInterfacePatchesMustBeInTheMesh) {
  CaseCheck misspelt = check();
  misspelt.interface_patches = {"wal"};
  EXPECT_CONTAINS(error_message<CaseError>([&] { misspelt.run(); }),
                  file("constant/polyMesh/boundary") +
                      ": solver 'fluid': interface patch 'wal' is not in the mesh (its patches: "
                      "inlet, wall); did you mean 'wall'?");
  std::filesystem::remove(directory_ / "constant/polyMesh/boundary");
  EXPECT_CONTAINS(error_message<CaseError>([&] { check().run(); }), "the case has no mesh");
}

TEST_F(CaseCheckTest, TheDensityMustBeGiven) {
  write("constant/transportProperties", "transportModel Newtonian;\nnu 1e-6;\n");
  EXPECT_CONTAINS(
      error_message<CaseError>([&] { check().run(); }),
      file("constant/transportProperties") + ": solver 'fluid': the fluid density rho is missing");
}

TEST_F(CaseCheckTest, AParallelRunNeedsAGeometricDecompositionIntoAsManyParts) {
  CaseCheck parallel = check();
  parallel.cores = 2;
  EXPECT_CONTAINS(error_message<CaseError>([&] { parallel.run(); }),
                  file("system/decomposeParDict") + ": cannot read the file");
  write("system/decomposeParDict", "numberOfSubdomains 4;\nmethod simple;\n");
  EXPECT_CONTAINS(
      error_message<CaseError>([&] { parallel.run(); }),
      file("system/decomposeParDict") +
          ":11: solver 'fluid': numberOfSubdomains 4 differs from the solver's cores 2");
  write("system/decomposeParDict", "numberOfSubdomains 2;\nmethod scotch;\n");
  EXPECT_CONTAINS(error_message<CaseError>([&] { parallel.run(); }),
                  file("system/decomposeParDict") + ":12: solver 'fluid': method scotch");
  write("system/decomposeParDict", "numberOfSubdomains 2;\nmethod hierarchical;\n");
  EXPECT_NO_THROW(parallel.run());
}

TEST(OpenFoamWrapper, ReadsItsKeysAndStartsCocoppPimpleFoamOnThePatches) {
  RunSettings run;
  run.delta_t = 0.001;
  run.case_directory = "/case";
  const Settings settings = Settings::load_string(
      "type: openfoam\nname: fluid\nworking_directory: tube\nboundary_names: [wall, top]\n",
      "case.yaml");
  const auto wrapper = SolverWrapperRegistry::instance().create(settings, run);
  settings.check_unused_keys();
  const auto& process = dynamic_cast<const ProcessSolverWrapper&>(*wrapper);
  ASSERT_EQ(process.command().size(), 3u);
  EXPECT_EQ(std::filesystem::path(process.command()[0]).filename(), "cocoppPimpleFoam");
  EXPECT_EQ(process.command()[1], "-patches");
  EXPECT_EQ(process.command()[2], "(wall top)");
  EXPECT_EQ(process.working_directory(), "/case/tube");

  const Settings parallel = Settings::load_string(
      "type: openfoam\nworking_directory: tube\nboundary_names: [wall]\ncores: 2\n", "case.yaml");
  const auto parallel_wrapper = SolverWrapperRegistry::instance().create(parallel, run);
  const auto& mpi = dynamic_cast<const ProcessSolverWrapper&>(*parallel_wrapper);
  const std::vector<std::string> expected = {"mpirun",
                                             "--allow-run-as-root",
                                             "--oversubscribe",
                                             "-np",
                                             "2",
                                             "-x",
                                             "WM_PROJECT_DIR",
                                             "-x",
                                             "COCOPP_TRANSPORT",
                                             "-x",
                                             "COCOPP_CHANNEL"};
  ASSERT_GE(mpi.command().size(), expected.size() + 4);
  EXPECT_EQ(
      std::vector<std::string>(mpi.command().begin(), mpi.command().begin() + expected.size()),
      expected);
  EXPECT_EQ(std::filesystem::path(mpi.command()[expected.size()]).filename(), "cocoppPimpleFoam");
  EXPECT_EQ(mpi.command()[expected.size() + 1], "-parallel");

  const Settings missing = Settings::load_string(
      "type: openfoam\nworking_directory: tube\nboundary_names: [wall, wall]\n", "case.yaml");
  EXPECT_CONTAINS(
      error_message<CaseError>([&] { SolverWrapperRegistry::instance().create(missing, run); }),
      "patch 'wall' is listed twice");
}

// A film's sensitivity_probe becomes cocoppPimpleFoam's COCOPP_SENSITIVITY_PROBE, which the
// case's key sets whatever the coupler's environment holds; a probe of a parallel run or of a
// case without its film's gap is refused at its line.
TEST(OpenFoamWrapper, ASensitivityProbeKeyBecomesTheFilmsEnvironment) {
  RunSettings run;
  run.delta_t = 0.001;
  run.case_directory = "/case";
  const std::string film =
      "type: openfoam\nworking_directory: fluid\nboundary_names: [wire]\ngap_patch: die\n";
  const Settings settings = Settings::load_string(
      film + "sensitivity_probe:\n  file: sensitivity.txt\n  hat: 3\n", "case.yaml");
  const auto wrapper = SolverWrapperRegistry::instance().create(settings, run);
  settings.check_unused_keys();
  const auto& process = dynamic_cast<const ProcessSolverWrapper&>(*wrapper);
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"COCOPP_SENSITIVITY_PROBE", "every 1e-08 sensitivity.txt warm hat=3"}};
  EXPECT_EQ(process.case_environment(), expected);

  const Settings step = Settings::load_string(
      film + "sensitivity_probe: {file: p.txt, step: 66, move: 2.0e-8, start: cold}\n",
      "case.yaml");
  const auto at_step = SolverWrapperRegistry::instance().create(step, run);
  EXPECT_EQ(dynamic_cast<const ProcessSolverWrapper&>(*at_step).case_environment().at(0).second,
            "66 2e-08 p.txt cold hat=1");

  const auto refused = [&](const std::string& text) {
    const Settings bad = Settings::load_string(text, "case.yaml");
    return error_message<CaseError>([&] { SolverWrapperRegistry::instance().create(bad, run); });
  };
  EXPECT_CONTAINS(
      refused(film + "cores: 2\nsensitivity_probe: {file: p.txt}\n"),
      "case.yaml:6:20: 'sensitivity_probe': the film probes itself in a serial run only");
  EXPECT_CONTAINS(refused("type: openfoam\nworking_directory: fluid\nboundary_names: [wire]\n"
                          "sensitivity_probe: {file: p.txt}\n"),
                  "give its gap_patch too");
  EXPECT_CONTAINS(refused(film + "sensitivity_probe: {file: p.txt, start: hot}\n"), "start");
  EXPECT_CONTAINS(refused(film + "sensitivity_probe: {file: p.txt, step: 0}\n"), "step");
}

}  // namespace
}  // namespace cocopp::openfoam
