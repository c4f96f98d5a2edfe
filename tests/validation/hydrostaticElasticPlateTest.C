/*---------------------------------------------------------------------------*\
Description
    Validation (c): the tutorial hydrostaticElasticPlate, run as a user runs
    it (blockMesh, spemMeshConvert, spemFoam, to its 0.5 s with the plate
    sub-cycled) at nx = 20 and 40 cells across the plate, against the
    analytical mid-span deflection of its referenceData/: the 2D plate in
    plane strain converges at first order to the shear-corrected
    (Timoshenko) value, its error halving from L/20 to L/40 (measured
    -5.67 % and -2.72 %; Euler-Bernoulli -2.24 % and +0.82 %), and its
    clamped ends carry the weight of water and plate (within 0.24 % at
    L/40). Sub-cycling (solidSubCycling) does not change the answer: at
    L/20 the run with one step for everything settles 0.20 % from the
    sub-cycled one. With method multiResolutionSPEM (the paper's refined
    particles over coarse elements, issue 15) the deflection converges
    from L/20 to L/40 as SPEM's does.

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

//- Weight of the water column and the plate per unit depth, (rho g H +
//  rho_s g t) L [N/m] (referenceData/analytical.md): the clamped ends' load
const double plateWeight = (1000*9.81*2 + 2700*9.81*0.05)*1;

//- The clamped ends' vertical load at the end of the run [N/m], from the
//  last row of plateLoad.dat (the force of the plate on its clamps, Fy < 0)
double endLoad(const fs::path& caseDir)
{
    std::ifstream is(caseDir/"postProcessing/plateLoad/0/plateLoad.dat");
    std::string line, last;
    while (std::getline(is, line))
    {
        if (!line.empty() && line[0] != '#') last = line;
    }
    std::istringstream ls(last);
    double t = 0, fx = 0, fy = 0;
    ls >> t >> fx >> fy;
    EXPECT_GT(t, 0) << "plateLoad.dat empty";
    return -fy;
}

struct settled
{
    double deflection;
    double load;
};

//- Run the tutorial at nx cells across, subCycling on (its default) or
//  off, with its method or another; the settled mid-span Dy and the ends'
//  load at the end
settled runTutorial
(
    const int nx,
    const std::string& subCycling = "on",
    const std::string& method = ""
)
{
    const fs::path source =
        fs::path(SPEM_PROJECT_DIR)/"tutorials/hydrostaticElasticPlate";
    const fs::path caseDir =
        tutorialCases::casesDir()
       /(
            "spemHydrostaticPlate_nx" + std::to_string(nx) + "_" + subCycling
          + method
        );
    fs::remove_all(caseDir);
    fs::create_directories(caseDir.parent_path());
    fs::copy(source, caseDir, fs::copy_options::recursive);
    // The tutorial folder may hold a user's run: clean the copy with the
    // tutorial's own Allclean
    EXPECT_EQ(std::system(("'" + (caseDir/"Allclean").string() + "'").c_str()), 0);
    replaceEntry(caseDir/"system/blockMeshDict", "nx", std::to_string(nx));
    replaceEntry(caseDir/"system/controlDict", "subCycling", subCycling);
    replaceEntry(caseDir/"system/controlDict", "writeInterval", "0.5");
    if (!method.empty())
    {
        replaceEntry(caseDir/"system/spemSchemes", "method", method);
    }

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
        if (status != 0) return {0, 0};
    }
    const settled result{settledDeflection(caseDir), endLoad(caseDir)};
    if (!::testing::Test::HasFailure()) fs::remove_all(caseDir);
    return result;
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

    std::map<int, double> errorT;
    std::map<int, double> loadError;
    for (const int nx : {20, 40})
    {
        const settled s = runTutorial(nx);
        ASSERT_FALSE(HasFailure());
        errorT[nx] = std::abs(s.deflection/wT - 1);
        loadError[nx] = s.load/plateWeight - 1;
        std::printf
        (
            "hydrostaticElasticPlate L/%d: mid-span Dy %.5e m; Euler-Bernoulli"
            " %.5e m (error %+.2f %%); shear-corrected %.5e m (error %+.2f %%);"
            " load on the clamped ends %.1f N/m (%+.2f %% of the weight)\n",
            nx, s.deflection, wEB, 100*(s.deflection/wEB - 1), wT,
            100*(s.deflection/wT - 1), s.load, 100*loadError[nx]
        );
    }
    // First order: the error halves (measured ratio 0.48); a run that
    // stops converging fails
    EXPECT_LT(errorT[40], 0.6*errorT[20]) << "no first-order convergence";
    EXPECT_LE(errorT[40], 0.05);
    // The ends carry the weight: 0.24 % short at L/40; the paper's
    // interpolated traction (eq. 25) put 0.7 % on top of it
    EXPECT_LT(std::abs(loadError[40]), 0.005);
}


TEST(Validation, hydrostaticElasticPlateSubCycledAsWithOneStep)
{
    // L/20: 1,800 steps of the water (87 plate sub-steps each) against
    // 155,000 steps for everything to 0.5 s
    const settled subCycled = runTutorial(20, "on");
    const settled oneStep = runTutorial(20, "off");
    ASSERT_FALSE(HasFailure());
    const double difference = subCycled.deflection/oneStep.deflection - 1;
    std::printf
    (
        "hydrostaticElasticPlate L/20: mid-span Dy %.5e m sub-cycled, %.5e m"
        " with one step for everything (%+.3f %%); loads %.1f and %.1f N/m\n",
        subCycled.deflection, oneStep.deflection, 100*difference,
        subCycled.load, oneStep.load
    );
    // Measured 0.20 %; twice that, inside the 0.5 % the sub-cycling must
    // keep to
    EXPECT_LT(std::abs(difference), 0.004);
}


TEST(Validation, hydrostaticElasticPlateWithRefinedParticlesConverges)
{
    // The paper's set-up of sect. 3.1 (issue 15): the top 0.5 m refined
    // particles (three per element) over coarse elements. The deflection
    // converges towards the shear-corrected value from L/20 to L/40
    // (measured 4.89 and 2.78 %, as SPEM's 5.67 and 2.72 %), and the ends
    // carry the weight (measured -0.38 % at L/40)
    const std::map<std::string, double> ref = reference
    (
        fs::path(SPEM_PROJECT_DIR)/"tutorials/hydrostaticElasticPlate"
    );
    ASSERT_EQ(ref.count("Dy_Timoshenko"), 1u);
    const double wT = ref.at("Dy_Timoshenko");
    std::map<int, settled> runs;
    for (const int nx : {20, 40})
    {
        runs[nx] = runTutorial(nx, "on", "multiResolutionSPEM");
        ASSERT_FALSE(HasFailure());
        std::printf
        (
            "hydrostaticElasticPlate L/%d, multiResolutionSPEM: mid-span Dy"
            " %.5e m, shear-corrected %.5e m (error %+.2f %%); ends %.1f N/m"
            " (%+.2f %% of the weight)\n",
            nx, runs[nx].deflection, wT, 100*(runs[nx].deflection/wT - 1),
            runs[nx].load, 100*(runs[nx].load/plateWeight - 1)
        );
    }
    const double e20 = std::abs(runs[20].deflection/wT - 1);
    const double e40 = std::abs(runs[40].deflection/wT - 1);
    EXPECT_LT(e40, e20) << "no convergence from L/20 to L/40";
    EXPECT_LE(e40, 0.05);
    EXPECT_LT(std::abs(runs[40].load/plateWeight - 1), 0.008);
}
