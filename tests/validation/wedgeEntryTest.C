/*---------------------------------------------------------------------------*\
Description
    Validation on the wedgeWaterEntry tutorial at a coarse resolution
    (paper sect. 3.2), run as a user runs it: a 30 deg wedge 0.5 m wide in
    free fall (241 kg/m, held in x and rotation) enters still water at
    6.15 m/s.

    While the water has not reached the chines (the upper corners of the
    V), the wedge is a similarity problem: at constant speed V the
    vertical force per unit length grows linearly in time,
        F = C rho V^3 t,
    with C = pi/tan^2(beta) = 9.42 (von Karman: the added mass of a flat
    plate as wide as the wedge at the undisturbed water level) and
    C = pi^3/(4 tan^2(beta)) = 23.25 (Wagner: the wetted width raised by
    the pile-up of the water, (pi/2)^2 times von Karman). The fully
    nonlinear similarity solution (Zhao & Faltinsen 1993) lies between
    them, nearer Wagner; the drop test of Zhao, Faltinsen & Aarsnes (1996)
    lies between them too. The wedge slows down by a few per cent over
    the window, so the coefficient is taken with the current speed,
        C(t) = F(t)/(rho V(t)^3 (t - t0)),
    t0 the time the keel reaches the still water level.

    The window: from the time the wetted half-width is 4 particle
    spacings (Wagner's estimate, c = (pi/2) V t/tan(beta), the faster
    one), before which the force is a few particles' worth and dominated
    by resolution, until 0.9 times the time Wagner's wetted half-width
    reaches the chine (0.25 m). The geometric (von Karman) estimate of the
    chine wetting, 0.023 s, is later; the measured force peaks at about
    0.015 s, which is Wagner's, so the window ends before either.

    The check uses the mean of C over the samples in the window, not each
    sample: the force of a weakly compressible particle method carries
    acoustic noise (the impact's pressure waves, c = 100 m/s) that makes
    single samples scatter by tens of per cent at this resolution, while
    the similarity law is about the mean growth. The fraction of samples
    inside the bounds is printed as well.

    Also: the wedge is moving at 6.15 m/s (within 1 %) when it reaches the
    water, and it decelerates: its speed at the end of the window is lower
    than at t0.

    And (issue 15, case II of the paper's sect. 3.2): multiResolutionSPEM
    on coarse elements against SPEM at the same local resolution, the
    peak force within 5 % and the wedge's speed closer to it than with
    SPEM on the coarse elements.

\*---------------------------------------------------------------------------*/

#include "testFiles.H"
#include "tutorialCases.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{

using testFiles::replaceEntry;
using tutorialCases::copyTutorial;
using tutorialCases::curveDifference;
using tutorialCases::readTable;
using tutorialCases::runCase;

const double pi = 3.14159265358979323846;
const double beta = 30*pi/180;      // deadrise angle
const double halfWidth = 0.25;      // [m]
const double gap = 0.001;           // keel above the water at t = 0 [m]
const double V0 = 6.15;             // entry speed [m/s]
const double rho = 1000;
const double cVonKarman = pi/std::pow(std::tan(beta), 2);
const double cWagner = std::pow(pi, 3)/(4*std::pow(std::tan(beta), 2));

//- Coarse resolution: cells across the wedge's width (blockMeshDict nx)
const int nx = 20;

} // End anonymous namespace


TEST(WedgeWaterEntry, forceBetweenVonKarmanAndWagnerBeforeChineWetsAndDecelerates)
{
    const fs::path caseDir = copyTutorial("wedgeWaterEntry", "wedgeEntryTest");
    replaceEntry(caseDir/"system/blockMeshDict", "nx", std::to_string(nx));
    replaceEntry(caseDir/"system/controlDict", "endTime", "0.016");
    replaceEntry(caseDir/"system/controlDict", "writeInterval", "0.008");
    ASSERT_TRUE(runCase(caseDir));

    const std::vector<std::vector<double>> rows =
        readTable(caseDir/"postProcessing/wedge/0/wedge.dat");
    ASSERT_GT(rows.size(), 20u);
    ASSERT_GE(rows.back().size(), 10u);
    EXPECT_NEAR(rows.back()[0], 0.016, 1e-4) << "the run did not reach endTime";

    // Time the keel reaches y = 0: the keel starts at y = gap, the centre
    // of mass moves as the keel does (no rotation)
    const double y0 = rows.front()[2] + V0*rows.front()[0];  // c.o.m. at t = 0
    // (the first sample may come after it: t = 0 at rest position first)
    std::vector<std::vector<double>> path{{0, 0, y0, 0, 0, -V0}};
    path.insert(path.end(), rows.begin(), rows.end());
    double t0 = -1, vAtT0 = 0;
    for (std::size_t i = 1; i < path.size(); ++i)
    {
        const double d0 = y0 - path[i - 1][2], d1 = y0 - path[i][2];
        if (d0 <= gap && d1 > gap)
        {
            const double w = (gap - d0)/(d1 - d0);
            t0 = path[i - 1][0] + w*(path[i][0] - path[i - 1][0]);
            vAtT0 = -(path[i - 1][5] + w*(path[i][5] - path[i - 1][5]));
            break;
        }
    }
    ASSERT_GT(t0, 0) << "the wedge never reached the water";

    // Particle spacing of the water elements: two triangles per square
    // cell of side W/nx, one particle per triangle
    const double spacing = (2*halfWidth/nx)/std::sqrt(2.0);
    const double tanBeta = std::tan(beta);
    const double tStart = 4*spacing*tanBeta/(0.5*pi*V0);
    const double tChineWagner = halfWidth*tanBeta/(0.5*pi*V0);
    const double tEnd = 0.9*tChineWagner;

    double sumC = 0, vEnd = vAtT0, tLast = 0;
    int n = 0, inside = 0;
    for (const auto& row : rows)
    {
        const double t = row[0] - t0;
        if (t < tStart || t > tEnd) continue;
        const double V = -row[5], Fy = row[8];
        const double C = Fy/(rho*V*V*V*t);
        sumC += C;
        ++n;
        if (C >= cVonKarman && C <= cWagner) ++inside;
        vEnd = V;
        tLast = t;
    }
    ASSERT_GT(n, 5) << "too few samples in the window";
    const double meanC = sumC/n;

    std::printf
    (
        "wedgeWaterEntry nx %d: keel at the water at t0 = %.3e s, V = %.4f m/s;"
        " window t - t0 = %.4f .. %.4f s (%d samples)\n"
        "  mean F/(rho V^3 t) = %.2f (von Karman %.2f, Wagner %.2f);"
        " %d of %d samples between them\n"
        "  speed %.4f m/s at t - t0 = %.4f s: %.3f m/s lost,"
        " mean deceleration %.1f m/s2\n",
        nx, t0, vAtT0, tStart, tEnd, n, meanC, cVonKarman, cWagner, inside,
        n, vEnd, tLast, vAtT0 - vEnd, (vAtT0 - vEnd)/tLast
    );

    EXPECT_NEAR(vAtT0, V0, 0.01*V0) << "not at the entry speed at contact";
    EXPECT_GE(meanC, cVonKarman);
    EXPECT_LE(meanC, cWagner);
    EXPECT_LT(vEnd, vAtT0) << "the wedge did not decelerate";
}


namespace
{

//- The wedge's vertical force over time of a copy of the tutorial run
//  with method at nx to 0.017 s: past the force peak (about 13 ms) and
//  Wagner's chine wetting (15 ms). edit, if given, changes the copy
//  before the run
std::vector<std::vector<double>> wedgeForce
(
    const std::string& method,
    const int cells,
    const std::string& copyName,
    const std::function<void(const fs::path&)>& edit = nullptr
)
{
    const fs::path caseDir = copyTutorial("wedgeWaterEntry", copyName);
    replaceEntry(caseDir/"system/blockMeshDict", "nx", std::to_string(cells));
    replaceEntry(caseDir/"system/spemSchemes", "method", method);
    replaceEntry(caseDir/"system/controlDict", "endTime", "0.017");
    replaceEntry(caseDir/"system/controlDict", "writeInterval", "1");
    if (edit) edit(caseDir);
    if (!runCase(caseDir)) return {};
    return readTable(caseDir/"postProcessing/wedge/0/wedge.dat");
}

//- Largest force sample (time, Fy) and largest mean force over a window
//  of width w centred on a sample, the samples in it weighted alike
//  (steps change by under 10 % within 1 ms): (time, mean Fy)
struct forcePeaks
{
    double tRaw, raw, tMean, mean;
};

forcePeaks peaks(const std::vector<std::vector<double>>& rows, const double w)
{
    forcePeaks p{0, -1e300, 0, -1e300};
    for (std::size_t i = 0; i < rows.size(); ++i)
    {
        const double t = rows[i][0];
        if (rows[i][8] > p.raw) p = {t, rows[i][8], p.tMean, p.mean};
        if (t - w/2 < rows.front()[0] || t + w/2 > rows.back()[0]) continue;
        double sum = 0;
        int n = 0;
        for (const auto& r : rows)
        {
            if (std::abs(r[0] - t) <= w/2) { sum += r[8]; ++n; }
        }
        if (sum/n > p.mean) { p.tMean = t; p.mean = sum/n; }
    }
    return p;
}

} // End anonymous namespace


// Issue 15 (paper sect. 3.2, case II: uniform cells): multiResolutionSPEM
// on coarse elements against SPEM at the same local resolution. Each
// converted triangle (a right-split square cell of side s) becomes three
// particles of spacing sqrt(s^2/6), which is SPEM's one particle per
// triangle, sqrt(s'^2/2), at s' = s/sqrt(3): nx 20 against nx 20 sqrt(3)
// = 34.6, rounded to 35. The bound: peak vertical force within 5 %.
// The force carries the impact's acoustic ringing (c = 100 m/s, single
// samples scatter by tens of per cent): the peak of the 1 ms mean (the
// tutorial's plot averages over 1 ms) is asserted; the peak sample
// (-3.94 % today) is printed, not asserted, being one sample of that
// noise.
// The peak alone hardly depends on the resolution (SPEM at nx 20 has it
// within 4 % too, and the ringing makes the force curves differ by 13-14 %
// of the peak RMS whatever the method), so the wedge's speed, the force's
// time integral, must also come closer to the fine run's than with SPEM on
// the same coarse elements (measured: RMS difference 0.024 against 0.040
// m/s, of 1.15 m/s lost by 0.017 s).
TEST(WedgeWaterEntry, multiResolutionPeakForceAsSPEMAtTheSameLocalResolution)
{
    const int coarse = 20, fine = 35;
    const auto multi =
        wedgeForce("multiResolutionSPEM", coarse, "wedgeEntryMultiRes");
    const auto spem = wedgeForce("SPEM", fine, "wedgeEntryFineSPEM");
    ASSERT_GT(multi.size(), 20u) << "the multiResolutionSPEM run failed";
    ASSERT_GT(spem.size(), 20u) << "the SPEM run failed";
    EXPECT_NEAR(multi.back()[0], 0.017, 1e-4);
    EXPECT_NEAR(spem.back()[0], 0.017, 1e-4);

    const auto coarseSpem = wedgeForce("SPEM", coarse, "wedgeEntryCoarseSPEM");
    ASSERT_GT(coarseSpem.size(), 20u) << "the coarse SPEM run failed";
    for (const auto* rows : {&multi, &spem, &coarseSpem})
    {
        for (const auto& row : *rows) ASSERT_GE(row.size(), 10u);
    }

    const forcePeaks m = peaks(multi, 1e-3), s = peaks(spem, 1e-3);
    const double rmsMulti = curveDifference(multi, spem, 5).first;
    const double rmsCoarse = curveDifference(coarseSpem, spem, 5).first;
    const double dRaw = m.raw/s.raw - 1, dMean = m.mean/s.mean - 1;
    std::printf
    (
        "wedgeWaterEntry case II to 0.017 s: multiResolutionSPEM nx %d"
        " against SPEM nx %d (%zu and %zu steps)\n"
        "  peak Fy %.0f N/m at %.2f ms against %.0f N/m at %.2f ms"
        " (%+.2f %%)\n"
        "  peak of the 1 ms mean %.0f N/m at %.2f ms against %.0f N/m at"
        " %.2f ms (%+.2f %%)\n"
        "  RMS difference of the wedge's speed from SPEM nx %d's:"
        " %.4f m/s; SPEM nx %d's %.4f m/s (speed lost %.3f m/s)\n",
        coarse, fine, multi.size(), spem.size(), m.raw, 1e3*m.tRaw, s.raw,
        1e3*s.tRaw, 100*dRaw, m.mean, 1e3*m.tMean, s.mean, 1e3*s.tMean,
        100*dMean, fine, rmsMulti, coarse, rmsCoarse,
        spem.back()[5] - spem.front()[5]
    );
    EXPECT_LT(rmsMulti, rmsCoarse)
        << "the refined particles bring the wedge's speed no closer to the"
           " fine run's than the coarse elements alone";
    EXPECT_LT(std::abs(dMean), 0.05);
}


// Issue 15, item 5 (paper sect. 3.2: a preset region of refined particles
// "much smaller than the solid structure" round the entry point, and a
// refined region that "changes with the evolution of the fluid-structure
// interfaces"): a preset box 0.2 m x 0.05 m (the tutorial's is 1 m x
// 0.35 m) and conversion/bodyReach 3, so that the elements within three
// particle supports (kappa h of one particle per element, 0.046 m at nx
// 20) of the wedge become refined particles as it enters. At 0.017 s the
// keel is 0.096 m deep, below the box:
// - the refined particles fill the layer under the keel: the lowest lies
//   at least 3 kappa h less a cell (elements with a node in the layer
//   convert, their particles lie within a cell of it) below the keel.
//   Measured: 0.165 m below it (bodyReach 1: 0.059 m, which fails);
// - the wedge's speed is nearer the fine SPEM's (nx 35, the tutorial's
//   box) than SPEM's on the same coarse elements, as with the tutorial's
//   box in the test above. Measured: 0.021 against 0.040 m/s RMS.
// It ends with 1,320 particles where the tutorial's box ends with 3,360
// (the cost of the paper's set-up: benchmarks/README.md, Table 1).
TEST(WedgeWaterEntry, multiResolutionRefinedRegionFollowsTheWedge)
{
    const int coarse = 20, fine = 35;
    const int bodyReach = 3;
    const auto papersSetUp = [&](const fs::path& caseDir)
    {
        // The box's corners and bodyReach, in the conversion dictionary
        const fs::path schemes = caseDir/"system/spemSchemes";
        for
        (
            const auto& [from, to] :
            {
                std::pair<std::string, std::string>
                {"min     (-0.5 -0.35 0);", "min (-0.1 -0.05 0);"},
                {"max     (0.5 0 0);", "max (0.1 0 0);"},
                {
                    "bodyReach        1;",
                    "bodyReach " + std::to_string(bodyReach) + ";"
                }
            }
        )
        {
            ASSERT_NO_FATAL_FAILURE(testFiles::replaceText(schemes, from, to));
        }
        // The state at the end
        replaceEntry(caseDir/"system/controlDict", "writeInterval", "0.017");
    };
    const auto multi = wedgeForce
    (
        "multiResolutionSPEM", coarse, "wedgeEntryMultiResFollows",
        papersSetUp
    );
    const auto spem = wedgeForce("SPEM", fine, "wedgeEntryFollowsFineSPEM");
    const auto coarseSpem =
        wedgeForce("SPEM", coarse, "wedgeEntryFollowsCoarseSPEM");
    for (const auto* rows : {&multi, &spem, &coarseSpem})
    {
        ASSERT_GT(rows->size(), 20u) << "a run failed";
        for (const auto& row : *rows) ASSERT_GE(row.size(), 10u);
    }

    // The keel (at y = 0.001 m at t = 0) at the end, from the body's
    // reference point, which starts at y(t1) - v(t1) t1
    const double y0 = multi[0][2] - multi[0][5]*multi[0][0];
    const double keel = 0.001 + multi.back()[2] - y0;
    const fs::path state =
        tutorialCases::casesDir()/"wedgeEntryMultiResFollows/0.017/spem";
    const std::vector<double> x =
        testFiles::readFoamList(state/"particlePositions", 3);
    ASSERT_GT(x.size(), 3u) << state;
    double lowest = 0;
    for (std::size_t i = 1; i < x.size(); i += 3) lowest = std::min(lowest, x[i]);

    // kappa h: WendlandC2's 2, 1.3 x the spacing of one particle per
    // right triangle of half a square cell of side 0.5/nx
    const double cell = 0.5/coarse;
    const double kappaH = 2*1.3*cell/std::sqrt(2.0);
    const double rmsMulti = curveDifference(multi, spem, 5).first;
    const double rmsCoarse = curveDifference(coarseSpem, spem, 5).first;
    std::printf
    (
        "wedgeWaterEntry, multiResolutionSPEM nx %d, preset box 0.2 m x"
        " 0.05 m, bodyReach %d: %zu particles at %.4f s; keel at y = %.4f"
        " m, lowest particle %.4f m below it (at least %.4f m asked)\n"
        "  RMS difference of the wedge's speed from SPEM nx %d's: %.4f m/s;"
        " SPEM nx %d's %.4f m/s\n",
        coarse, bodyReach, x.size()/3, multi.back()[0], keel, keel - lowest,
        bodyReach*kappaH - cell, fine, rmsMulti, coarse, rmsCoarse
    );
    EXPECT_LT(keel, -0.05) << "the keel did not leave the preset box";
    EXPECT_LT(lowest, keel - (bodyReach*kappaH - cell))
        << "the refined particles do not fill the layer under the keel";
    EXPECT_LT(rmsMulti, rmsCoarse);
}


// ************************************************************************* //
