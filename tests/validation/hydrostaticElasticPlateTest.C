/*---------------------------------------------------------------------------*\
Description
    Validation (c): the tutorial hydrostaticElasticPlate, run as a user runs
    it (blockMesh, spemMeshConvert, spemFoam) at nx = 20 and 40 cells across
    the plate, against the analytical mid-span deflection of its
    referenceData/ (Euler-Bernoulli and shear-corrected). The run is cut to
    0.1 s: with the tutorial's damping every mode has decayed by e^-7.5.

\*---------------------------------------------------------------------------*/

#include "testFiles.H"
#include "tutorialCases.H"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{

using testFiles::readText;
using testFiles::replaceEntry;

//- Mean Dy over the last 10 % of the samples of midSpan.dat
double settledDeflection(const fs::path& caseDir)
{
    std::ifstream is(caseDir/"postProcessing/midSpan/0/midSpan.dat");
    std::vector<double> dy;
    std::string line;
    while (std::getline(is, line))
    {
        if (line.find('#') != std::string::npos) continue;
        std::istringstream ls(line);
        double t, dx, y;
        if (ls >> t >> dx >> y) dy.push_back(y);
    }
    EXPECT_GT(dy.size(), 100u) << "midSpan.dat too short";
    if (dy.empty()) return 0;
    const size_t first = dy.size() - dy.size()/10;
    double sum = 0;
    for (size_t i = first; i < dy.size(); ++i) sum += dy[i];
    return sum/(dy.size() - first);
}

std::map<std::string, double> reference(const fs::path& caseDir)
{
    std::ifstream is(caseDir/"referenceData/midSpanDeflection.dat");
    std::map<std::string, double> values;
    std::string line;
    while (std::getline(is, line))
    {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ls(line);
        std::string key;
        double v;
        if (ls >> key >> v) values[key] = v;
    }
    return values;
}

//- Run the tutorial at nx cells across; returns the settled mid-span Dy
double runTutorial(const int nx)
{
    const fs::path source =
        fs::path(SPEM_PROJECT_DIR)/"tutorials/hydrostaticElasticPlate";
    const fs::path caseDir =
        tutorialCases::casesDir()/("spemHydrostaticPlate_nx" + std::to_string(nx));
    fs::remove_all(caseDir);
    fs::create_directories(caseDir.parent_path());
    fs::copy(source, caseDir, fs::copy_options::recursive);
    // The tutorial folder may hold a user's run: clean the copy with the
    // tutorial's own Allclean
    EXPECT_EQ(std::system(("'" + (caseDir/"Allclean").string() + "'").c_str()), 0);
    replaceEntry(caseDir/"system/blockMeshDict", "nx", std::to_string(nx));
    replaceEntry(caseDir/"system/controlDict", "endTime", "0.1");
    replaceEntry(caseDir/"system/controlDict", "writeInterval", "0.05");

    const std::string run = "cd '" + caseDir.string() + "' && ";
    for
    (
        const std::string& program :
        {
            std::string("blockMesh"), std::string(SPEM_MESH_CONVERT),
            std::string(SPEM_FOAM)
        }
    )
    {
        const std::string name = fs::path(program).filename();
        const int status =
            std::system((run + program + " > log." + name + " 2>&1").c_str());
        EXPECT_EQ(status, 0) << name << " failed, see " << caseDir/("log." + name);
        if (status != 0) return 0;
    }
    const double dy = settledDeflection(caseDir);
    if (!::testing::Test::HasFailure()) fs::remove_all(caseDir);
    return dy;
}

} // End anonymous namespace


TEST(Validation, hydrostaticElasticPlateConvergesToPlateTheory)
{
    const std::map<std::string, double> ref = reference
    (
        fs::path(SPEM_PROJECT_DIR)/"tutorials/hydrostaticElasticPlate"
    );
    ASSERT_EQ(ref.count("Dy_EulerBernoulli"), 1u);
    ASSERT_EQ(ref.count("Dy_Timoshenko"), 1u);
    const double wEB = ref.at("Dy_EulerBernoulli");
    const double wT = ref.at("Dy_Timoshenko");

    std::map<int, double> errorEB;
    for (const int nx : {20, 40})
    {
        const double dy = runTutorial(nx);
        ASSERT_FALSE(HasFailure());
        errorEB[nx] = std::abs(dy/wEB - 1);
        std::printf
        (
            "hydrostaticElasticPlate L/%d: mid-span Dy %.5e m; Euler-Bernoulli"
            " %.5e m (error %+.2f %%); shear-corrected %.5e m (error %+.2f %%)\n",
            nx, dy, wEB, 100*(dy/wEB - 1), wT, 100*(dy/wT - 1)
        );
    }
    EXPECT_LT(errorEB[40], errorEB[20]) << "no convergence from L/20 to L/40";
    EXPECT_LE(errorEB[40], 0.05);
}
