/*---------------------------------------------------------------------------*\
Description
    Validation of the particle half (method SPH) on the tutorials, run as a
    user runs them (blockMesh, spemMeshConvert, spemFoam) on a copy of the
    case at a coarse resolution:
      - hydrostaticTank (nx 20, 800 particles, started hydrostatic and
        kept 2 s with the tutorial's damping): the pressure gradient of the
        particles within 2 % of rho g, the mean pressure of every band
        below the top fifth within 2 % of rho g (H - y), every band's
        within 2 % of the hydrostatic scale rho g H; every particle kept
        and inside the tank at every written time;
      - hydrostaticTank relaxed (nx 40, 3200 particles, sph/initialRelaxation
        and momentumGradient symmetrisedCorrection): every band up to the
        surface within 2 % of rho g (H - y), the column's height kept;
      - damBreak (nx 20, 1600 particles, up to the front reaching the far
        wall): the surge front against Martin and Moyce (1952) and
        Koshizuka and Oka (1996), every particle inside the tank.

\*---------------------------------------------------------------------------*/

#include "testFiles.H"
#include "tutorialCases.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{

using testFiles::readFoamList;
using testFiles::replaceEntry;
using tutorialCases::copyTutorial;
using tutorialCases::readTable;
using tutorialCases::runCase;

//- Written time directories (those with a particle state), in time order
std::vector<fs::path> particleStates(const fs::path& caseDir)
{
    std::vector<std::pair<double, fs::path>> times;
    for (const auto& e : fs::directory_iterator(caseDir))
    {
        if (!fs::exists(e.path()/"spem/particlePositions")) continue;
        times.push_back({std::stod(e.path().filename().string()), e.path()});
    }
    std::sort(times.begin(), times.end());
    std::vector<fs::path> dirs;
    for (const auto& t : times) dirs.push_back(t.second);
    return dirs;
}

//- Expect every particle of every written time inside [x0, x1] x [y0, inf)
//  and the particle count unchanged
void expectParticlesKeptInside
(
    const fs::path& caseDir,
    const size_t nParticles,
    const double x0,
    const double x1,
    const double y0
)
{
    const std::vector<fs::path> states = particleStates(caseDir);
    EXPECT_GE(states.size(), 3u);
    for (const fs::path& dir : states)
    {
        const std::vector<double> x = readFoamList(dir/"spem/particlePositions", 3);
        ASSERT_EQ(x.size(), 3*nParticles) << dir;
        size_t outside = 0;
        for (size_t i = 0; i < nParticles; ++i)
        {
            if (x[3*i] < x0 || x[3*i] > x1 || x[3*i + 1] < y0) ++outside;
        }
        EXPECT_EQ(outside, 0u) << "particles through a wall at " << dir;
    }
}

//- Mean height and mean pressure p = c^2 (rho - rho0) of the particles in
//  nBands horizontal bands of height H/nBands, away from the side walls
//  (0.1 W to 0.9 W, W = H)
struct band { double y, p; };
std::vector<band> hydrostaticBands
(
    const fs::path& state,
    const size_t n,
    const int nBands,
    const double H,
    const double rho0,
    const double c
)
{
    const std::vector<double> x = readFoamList(state/"spem/particlePositions", 3);
    const std::vector<double> rho = readFoamList(state/"spem/particleRho", 1);
    std::vector<band> bands;
    if (rho.size() != n || x.size() != 3*n) return bands;
    for (int b = 0; b < nBands; ++b)
    {
        const double y0 = b*H/nBands, y1 = y0 + H/nBands;
        double sumP = 0, sumY = 0;
        int count = 0;
        for (size_t i = 0; i < n; ++i)
        {
            const double px = x[3*i], py = x[3*i + 1];
            if (py < y0 || py >= y1 || px < 0.1*H || px > 0.9*H) continue;
            sumP += c*c*(rho[i] - rho0);
            sumY += py;
            ++count;
        }
        if (count == 0) return {};
        bands.push_back({sumY/count, sumP/count});
    }
    return bands;
}

//- Add entries to the sph sub-dictionary of a case's system/spemSchemes
void addSphEntries(const fs::path& caseDir, const std::string& entries)
{
    const fs::path file = caseDir/"system/spemSchemes";
    std::string text = testFiles::readText(file);
    const size_t at = text.find("sph\n{\n");
    ASSERT_NE(at, std::string::npos) << "no sph { in " << file;
    text.insert(at + 6, entries);
    std::ofstream(file) << text;
}

} // End anonymous namespace


TEST(SphValidation, hydrostaticTankPressureWithinTwoPercent)
{
    const fs::path caseDir = copyTutorial("hydrostaticTank", "spemHydrostaticTank");
    replaceEntry(caseDir/"system/blockMeshDict", "nx", "20");
    replaceEntry(caseDir/"system/controlDict", "endTime", "2");
    replaceEntry(caseDir/"system/controlDict", "writeInterval", "0.5");
    ASSERT_TRUE(runCase(caseDir));

    // Tutorial constants: W = H = 0.5 m, rho0 1000, c 25, g 9.81
    const double H = 0.5, rho0 = 1000, c = 25, g = 9.81;
    const size_t n = 800;
    expectParticlesKeptInside(caseDir, n, 0, H, 0);

    const fs::path last = particleStates(caseDir).back();
    const std::vector<double> x = readFoamList(last/"spem/particlePositions", 3);
    const std::vector<double> rho = readFoamList(last/"spem/particleRho", 1);
    ASSERT_EQ(rho.size(), n);

    // Mean pressure and mean height of the particles in 10 horizontal
    // bands, away from the side walls, against rho g (H - y) at the bands'
    // mean height
    const int nBands = 10;
    const std::vector<band> bands = hydrostaticBands(last, n, nBands, H, rho0, c);
    ASSERT_EQ(bands.size(), size_t(nBands));
    double bottomError = 0, largestOffset = 0, largestBelow = 0;
    for (int b = 0; b < nBands; ++b)
    {
        const double p = bands[b].p, y = bands[b].y;
        const double exact = rho0*g*(H - y);
        if (b == 0) bottomError = p/exact - 1;
        largestOffset = std::max(largestOffset, std::abs(p - exact));
        if (b < nBands - 2)
        {
            largestBelow = std::max(largestBelow, std::abs(p/exact - 1));
        }
        std::printf
        (
            "hydrostaticTank nx 20, t = %s s: band at mean y = %.4f m:"
            " p %.1f Pa, rho g (H - y) %.1f Pa, error %+.2f %% (%+.1f Pa,"
            " %+.2f %% of rho g H)\n",
            last.filename().c_str(), y, p, exact, 100*(p/exact - 1), p - exact,
            100*(p - exact)/(rho0*g*H)
        );
    }

    // The hydrostatic law: least-squares dp/dy of the particles below the
    // top tenth (truncated kernels at the surface) and away from the side
    // walls
    double sy = 0, sp = 0, syy = 0, syp = 0;
    int m = 0;
    double yTop = 0;
    for (size_t i = 0; i < n; ++i)
    {
        const double px = x[3*i], py = x[3*i + 1];
        yTop = std::max(yTop, py);
        if (py > 0.9*H || px < 0.1*H || px > 0.9*H) continue;
        const double p = c*c*(rho[i] - rho0);
        sy += py; sp += p; syy += py*py; syp += py*p;
        ++m;
    }
    const double slope = (m*syp - sy*sp)/(m*syy - sy*sy);
    std::printf
    (
        "hydrostaticTank nx 20: dp/dy %.1f Pa/m, -rho0 g %.1f Pa/m (%+.2f %%);"
        " bottom band %+.2f %%; highest particle %.4f m (%.4f m at t = 0)\n",
        slope, -rho0*g, 100*(slope/(-rho0*g) - 1), 100*bottomError, yTop,
        H - H/20/3
    );
    EXPECT_LT(std::abs(slope/(-rho0*g) - 1), 0.02);
    EXPECT_LT(std::abs(bottomError), 0.02);
    EXPECT_LT(largestOffset, 0.02*rho0*g*H);
    // Every band below the top fifth within 2 % of the local rho g (H - y)
    // (measured: at most 1.4 %, the band at 0.37 m; with the momentum
    // equation's symmetrised gradient correction, sphFluid.H, the bands
    // from 0.32 m up were 2.6-10 % low, a constant 45 Pa)
    EXPECT_LT(largestBelow, 0.02);

    // Not asserted (issue note): the top two bands, -2.7 % and -3.8 % of
    // the local rho g (H - y) (-21 and -11 Pa). The settled particles fill
    // about 0.7 % less height than their volumes m/rho add up to: their
    // mean height drops 2.5 mm within 0.1 s while their mean density stays
    // (to 1e-5). The barycentres of each cell, (2/3, 1/3) and (1/3, 2/3)
    // of it, are a close pair; the pairs open into an even staggered
    // lattice (measured by following the particles without reordering:
    // each moves 2 mm sideways, apart from its partner), the continuity
    // equation reads that opening as a dilation, and the column sinks by
    // 0.75 % of its height at constant density to carry its weight again.
    // The same with or without gradient correction or shifting, and at
    // nx 40 (top bands -3.5 and -7.8 %), so the error near the surface
    // does not shrink with resolution. With the initial relaxation and the
    // symmetrised correction (sphFluid.H) it does: next test
    if (!HasFailure()) fs::remove_all(caseDir);
}


TEST(SphValidation, hydrostaticTankRelaxedWithinTwoPercentUpToTheSurface)
{
    // The tutorial at nx 40 with the barycentres relaxed before the start
    // and the symmetrised corrected gradient in the momentum equation
    const fs::path caseDir =
        copyTutorial("hydrostaticTank", "spemHydrostaticTankRelaxed");
    replaceEntry(caseDir/"system/blockMeshDict", "nx", "40");
    replaceEntry(caseDir/"system/controlDict", "endTime", "2");
    replaceEntry(caseDir/"system/controlDict", "writeInterval", "0.5");
    addSphEntries
    (
        caseDir,
        "    momentumGradient symmetrisedCorrection;\n"
        "    initialRelaxation 400;\n"
    );
    ASSERT_TRUE(runCase(caseDir));

    const double H = 0.5, rho0 = 1000, c = 25, g = 9.81;
    const size_t n = 3200;
    expectParticlesKeptInside(caseDir, n, 0, H, 0);

    // Relaxed at t = 0: the particles left the barycentres
    const std::vector<fs::path> states = particleStates(caseDir);
    const std::vector<double> x0 =
        readFoamList(states.front()/"spem/particlePositions", 3);
    const std::vector<double> x1 =
        readFoamList(states.back()/"spem/particlePositions", 3);
    ASSERT_EQ(x0.size(), 3*n);
    ASSERT_EQ(x1.size(), 3*n);
    const double spacing = H/40;
    bool offBarycentre = false;
    double meanSink = 0;
    for (size_t i = 0; i < n; ++i)
    {
        // Barycentres of split right cells: (1/3, 2/3) or (2/3, 1/3)
        const double fx = std::fmod(x0[3*i]/spacing, 1.0);
        offBarycentre =
            offBarycentre
         || std::min(std::abs(fx - 1.0/3), std::abs(fx - 2.0/3)) > 0.02;
        meanSink += (x0[3*i + 1] - x1[3*i + 1])/n;
    }
    EXPECT_TRUE(offBarycentre) << "initialRelaxation moved no particle";

    // Every band, the top one too, within 2 % of the local rho g (H - y)
    // (measured: at most 1.4 %, the top band; without the two entries the
    // top bands are 3.8 and 8.5 % low at nx 40, README)
    const std::vector<band> bands =
        hydrostaticBands(states.back(), n, 10, H, rho0, c);
    ASSERT_EQ(bands.size(), 10u);
    double largest = 0;
    for (const band& b : bands)
    {
        const double exact = rho0*g*(H - b.y);
        std::printf
        (
            "hydrostaticTank relaxed, nx 40: band at mean y = %.4f m: p %.1f"
            " Pa, rho g (H - y) %.1f Pa, error %+.2f %%\n",
            b.y, b.p, exact, 100*(b.p/exact - 1)
        );
        largest = std::max(largest, std::abs(b.p/exact - 1));
    }
    std::printf
    (
        "hydrostaticTank relaxed, nx 40: largest band error %.2f %%, mean"
        " sink %.2f mm\n", 100*largest, 1e3*meanSink
    );
    EXPECT_LT(largest, 0.02);
    // The column keeps its height (the barycentres sink 2.1 mm at nx 40)
    EXPECT_LT(std::abs(meanSink), 0.5e-3);
    if (!HasFailure()) fs::remove_all(caseDir);
}


TEST(SphValidation, damBreakSurgeFrontAgainstExperiments)
{
    const fs::path caseDir = copyTutorial("damBreak", "spemDamBreak");
    replaceEntry(caseDir/"system/blockMeshDict", "nx", "20");
    replaceEntry(caseDir/"system/controlDict", "endTime", "0.3");
    replaceEntry(caseDir/"system/controlDict", "writeInterval", "0.05");
    ASSERT_TRUE(runCase(caseDir));

    const double a = 0.146, L = 4*a, g = 9.81;
    expectParticlesKeptInside(caseDir, 1600, 0, L, 0);

    // Our front: T = t sqrt(2 g/a), Z = front/a
    std::vector<double> T, Z;
    for (const auto& row : readTable(caseDir/"postProcessing/surgeFront/0/surgeFront.dat"))
    {
        T.push_back(row[0]*std::sqrt(2*g/a));
        Z.push_back(row[1]/a);
    }
    ASSERT_GT(T.size(), 100u);
    auto ours = [&](const double t)
    {
        const size_t k = std::lower_bound(T.begin(), T.end(), t) - T.begin();
        if (k == 0 || k >= T.size()) return std::nan("");
        const double w = (t - T[k - 1])/(T[k] - T[k - 1]);
        return (1 - w)*Z[k - 1] + w*Z[k];
    };

    const fs::path ref = fs::path(SPEM_PROJECT_DIR)/"tutorials/damBreak/referenceData";
    for (const char* data : {"MartinMoyce1952_surgeFront.dat", "KoshizukaOka1996_surgeFront.dat"})
    {
        // Experimental points before the front reaches the far wall
        std::vector<double> te, ze, zs;
        for (const auto& row : readTable(ref/data))
        {
            const double z = ours(row[0]);
            if (row[1] >= L/a || row[0] <= 0 || std::isnan(z) || z >= L/a - 0.05)
            {
                continue;
            }
            te.push_back(row[0]);
            ze.push_back(row[1]);
            zs.push_back(z);
        }
        ASSERT_GE(te.size(), 5u) << data;

        double worst = 0;
        for (size_t k = 0; k < te.size(); ++k)
        {
            const double e = zs[k]/ze[k] - 1;
            std::printf
            (
                "damBreak nx 20 vs %s: T %.3f Z exp %.3f ours %.3f (%+.1f %%)\n",
                data, te[k], ze[k], zs[k], 100*e
            );
            worst = std::max(worst, std::abs(e));
        }

        // Front speed dZ/dT: least-squares slopes over the same points
        // once the front runs (Z >= 1.4, after the initial collapse)
        auto slope = [&](const std::vector<double>& z)
        {
            double st = 0, sz = 0, stt = 0, stz = 0;
            int m = 0;
            for (size_t k = 0; k < te.size(); ++k)
            {
                if (ze[k] < 1.4) continue;
                st += te[k]; sz += z[k]; stt += te[k]*te[k]; stz += te[k]*z[k];
                ++m;
            }
            return (m*stz - st*sz)/(m*stt - st*st);
        };
        const double sExp = slope(ze), sOurs = slope(zs);
        std::printf
        (
            "damBreak nx 20 vs %s: largest front position error %.1f %%;"
            " front speed dZ/dT %.3f, experiment %.3f (%+.1f %%)\n",
            data, 100*worst, sOurs, sExp, 100*(sOurs/sExp - 1)
        );
        // The front must advance at the measured speed of Martin and Moyce
        // (the two experiments differ by 30 % in speed: Koshizuka and Oka's
        // is reported only). Its position leads the experiments by a nearly
        // constant time (about 0.2 in T, 17 ms), which releasing the column
        // at once cannot remove: the experiments' gate needed time to open
        // (see tutorials/damBreak/referenceData/README.md)
        if (std::string(data).find("MartinMoyce") == 0)
        {
            EXPECT_LT(std::abs(sOurs/sExp - 1), 0.10) << data;
        }
    }
    if (!HasFailure()) fs::remove_all(caseDir);
}


TEST(SphStability, damBreakStableBelowCriticalCourantNumberStopsCleanlyAbove)
{
    // Measured critical Courant number of the particles: 1.5-1.75 (coarse
    // dam break, nx 10, the most violent case); maxCo 1.25 must run, 2.5
    // must blow up and stop with the last good state written
    for (const double co : {1.25, 2.5})
    {
        const fs::path caseDir = copyTutorial
        (
            "damBreak", "spemDamBreakCo" + std::to_string(int(100*co))
        );
        replaceEntry(caseDir/"system/blockMeshDict", "nx", "10");
        replaceEntry(caseDir/"system/controlDict", "endTime", "0.5");
        replaceEntry(caseDir/"system/controlDict", "writeInterval", "0.1");
        replaceEntry(caseDir/"system/controlDict", "maxCo", std::to_string(co));
        std::ofstream(caseDir/"system/controlDict", std::ios::app)
            << "\nallowMaxCoAbove1 yes;\n";
        const std::string run = "cd '" + caseDir.string() + "' && ";
        ASSERT_EQ(std::system((run + "blockMesh > log.blockMesh 2>&1").c_str()), 0);
        ASSERT_EQ(std::system((run + SPEM_MESH_CONVERT + " > log.convert 2>&1").c_str()), 0);
        const int status = std::system((run + SPEM_FOAM + " > log.spemFoam 2>&1").c_str());
        const std::string log = testFiles::readText(caseDir/"log.spemFoam");
        if (co < 1.5)
        {
            EXPECT_EQ(status, 0) << "maxCo " << co << " blew up:\n" << log;
            expectParticlesKeptInside(caseDir, 400, 0, 0.584, 0);
        }
        else
        {
            EXPECT_NE(status, 0) << "maxCo " << co << " did not blow up";
            EXPECT_NE(log.find("Run stopped at time"), std::string::npos) << log;
            EXPECT_NE(log.find("last good state"), std::string::npos) << log;
            // The last good state is the last written time
            const std::vector<fs::path> states = particleStates(caseDir);
            ASSERT_FALSE(states.empty());
            EXPECT_NE(log.find(states.back().filename().string()), std::string::npos)
                << "last state " << states.back() << " not named in the log";
        }
        if (!HasFailure()) fs::remove_all(caseDir);
    }
}


// ************************************************************************* //
