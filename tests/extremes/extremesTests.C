/*---------------------------------------------------------------------------*\
Description
    Stability at the extremes (ctest label `extremes`): damBreak (method SPH)
    and damBreakElasticPlate (method SPEM), coarse and short, with one
    change at a time from the tutorial: resolution coarse and 2x fine, c /5
    and x10, E 1e4 and 1e9 (the plate), mu 0 and 1, maxCo 0.5 to 3 and
    gravity x10.

    Each case either runs to its end or stops with the message that names
    its cause and writes its last state; in both, every written state is
    checked here, independently of the solver's own checks: all values
    finite, no fluid particle through a wall (outside the tank by more than
    a kernel support), no element node below the floor or beyond the side
    walls. Where the flow passes c/10 the log must say so (the Mach
    warning); where maxCo is above 1 the log must warn that the step
    estimates hold only up to 1. On the plate, where the step is within its
    estimates (maxCo <= 1, g as given), the plate must stay still until the
    water reaches it (maxCo 1 moves it by 3e-7 m). maxCo above 1 is
    refused at the start unless allowMaxCoAbove1 is set: measured before,
    the plate's maxCo 1.5 and 2 ran to the end moving the plate by 6 and
    0.7 mm before the water arrived and throwing particles 3.6 m high, and
    damBreak's maxCo 2 put the surge front 105 % off; allowed, maxCo 3
    must blow up and stop with its last good state.

    The outcome of every case is printed in one line (the table of the
    issue's note).

\*---------------------------------------------------------------------------*/

#include "testFiles.H"
#include "tutorialCases.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using testFiles::readFoamList;
using testFiles::readText;

namespace
{

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

//- The tank of both tutorials: 4a x 4a (walls 4a high), open at the top
constexpr double a = 0.146;
constexpr double tankWidth = 4*a;

//- One change to a dictionary file of the case
struct edit
{
    std::string file, key, value;
};

struct extremeCase
{
    std::string name;
    std::string tutorial;
    int nx;
    double endTime;
    std::vector<edit> edits;
    //- The run must stop, and its log hold these (empty: it must run to
    //  its end)
    std::vector<std::string> stopMessage;
    //- The log must hold these (warnings)
    std::vector<std::string> warnings;
    //- The plate must stay still until the water arrives (t < 0.06 s)
    bool plateStillBeforeImpact;
};

std::ostream& operator<<(std::ostream& os, const extremeCase& c)
{
    return os << c.name;
}

const std::string spemProperties = "constant/spemProperties";
const std::string controlDict = "system/controlDict";
const std::string gravity = "constant/g";

const std::string machWarning = "the flow reaches Mach";
const std::string courantWarning = "the stable step estimates hold up to";
const std::vector<std::string> courantRefusal
{
    "FATAL IO ERROR", "maxCo", "is above 1", "allowMaxCoAbove1"
};
const std::vector<std::string> blowUp
{
    "Run stopped at time", "The last good state", "Reduce maxCo"
};

//- Set `key value;` (indented or not) in a dictionary file; added at its
//  end if it is not there
void setEntry(const fs::path& file, const std::string& key, const std::string& value)
{
    std::string text = readText(file);
    const std::regex entry("(^|\n)([ \t]*)" + key + "[ \t]+[^;\n]*;");
    if (!std::regex_search(text, entry))
    {
        std::ofstream(file, std::ios::app) << '\n' << key << ' ' << value << ";\n";
        return;
    }
    text = std::regex_replace
    (
        text, entry, "$1$2" + key + " " + value + ";",
        std::regex_constants::format_first_only
    );
    std::ofstream(file) << text;
}

//- The time directories with a complete state, in time order
std::vector<fs::path> writtenStates(const fs::path& caseDir)
{
    std::vector<std::pair<double, fs::path>> times;
    for (const auto& e : fs::directory_iterator(caseDir))
    {
        if (!fs::exists(e.path()/"spem"/"restartFiles")) continue;
        times.push_back({std::stod(e.path().filename().string()), e.path()});
    }
    std::sort(times.begin(), times.end());
    std::vector<fs::path> dirs;
    for (const auto& t : times) dirs.push_back(t.second);
    return dirs;
}

//- The first number after `key` in the log (NaN if none)
double numberAfter(const std::string& log, const std::string& key)
{
    std::smatch m;
    const std::regex re(key + "([-+0-9.eE]+)");
    if (!std::regex_search(log, m, re)) return NAN;
    return std::stod(m[1].str());
}

struct stateCheck
{
    std::size_t nStates = 0;
    std::size_t nonFinite = 0;
    std::size_t particlesThroughWalls = 0;
    std::size_t nodesThroughWalls = 0;
    //- Least margin to the walls (negative: outside) [m]
    double particleMargin = INFINITY, nodeMargin = INFINITY;
};

//- Every written state: finite, particles inside the tank within reach,
//  element nodes inside it
stateCheck checkStates(const fs::path& caseDir, const double reach)
{
    stateCheck c;
    for (const fs::path& dir : writtenStates(caseDir))
    {
        ++c.nStates;
        for (const char* name : {"points", "particlePositions"})
        {
            const fs::path f = dir/"spem"/name;
            if (!fs::exists(f)) continue;
            const bool particles = std::string(name) == "particlePositions";
            const std::vector<double> x = readFoamList(f, 3);
            for (std::size_t i = 0; i + 1 < x.size(); i += 3)
            {
                if (!std::isfinite(x[i]) || !std::isfinite(x[i + 1]))
                {
                    ++c.nonFinite;
                    continue;
                }
                // Distance inside the walls (negative: outside): left,
                // right and floor. Above the walls' top is the open air,
                // where the flow may splash: a particle beside the tank is
                // outside by the lesser of its distances to the wall and
                // to the air above the top
                const double side = std::min(x[i], tankWidth - x[i]);
                const double margin = std::min
                (
                    side < 0 ? std::max(side, x[i + 1] - tankWidth) : side,
                    x[i + 1]
                );
                if (particles)
                {
                    c.particleMargin = std::min(c.particleMargin, margin);
                    if (margin < -reach) ++c.particlesThroughWalls;
                }
                else
                {
                    c.nodeMargin = std::min(c.nodeMargin, margin);
                    // The contact keeps nodes on the walls to round-off
                    if (margin < -1e-9) ++c.nodesThroughWalls;
                }
            }
        }
        for (const char* name : {"U", "particleU", "particleRho"})
        {
            const fs::path f = dir/"spem"/name;
            if (!fs::exists(f)) continue;
            for (const double v : readFoamList(f, std::string(name) == "particleRho" ? 1 : 3))
            {
                if (!std::isfinite(v)) ++c.nonFinite;
            }
        }
    }
    return c;
}

//- Largest horizontal tip displacement of the plate before time t
double tipMotionBefore(const fs::path& caseDir, const double t)
{
    const std::vector<std::vector<double>> rows = tutorialCases::readTable
    (
        caseDir/"postProcessing"/"plateTip"/"0"/"plateTip.dat"
    );
    double largest = -1;
    for (const std::vector<double>& r : rows)
    {
        if (r.size() < 2 || r[0] >= t) continue;
        largest = std::max(largest, std::abs(r[1]));
    }
    return largest;
}

class Extremes : public ::testing::TestWithParam<extremeCase> {};

TEST_P(Extremes, runsCleanOrStopsForTheRightReason)
{
    const extremeCase& ec = GetParam();
    std::string tmpl = (fs::temp_directory_path()/"spemExtremes-XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    const fs::path caseDir = tutorialCases::copyTutorial
    (
        ec.tutorial, (fs::path(tmpl).filename()/ec.name).string()
    );
    testFiles::replaceEntry(caseDir/"system/blockMeshDict", "nx", std::to_string(ec.nx));
    std::ostringstream end;
    end << ec.endTime;
    testFiles::replaceEntry(caseDir/controlDict, "endTime", end.str());
    for (const edit& e : ec.edits)
    {
        setEntry(caseDir/e.file, e.key, e.value);
    }
    if (HasFatalFailure()) return;

    const std::string run = "cd '" + caseDir.string() + "' && ";
    ASSERT_EQ(std::system((run + "blockMesh > log.blockMesh 2>&1").c_str()), 0);
    ASSERT_EQ
    (
        std::system((run + SPEM_MESH_CONVERT + " > log.spemMeshConvert 2>&1").c_str()),
        0
    );
    const auto start = std::chrono::steady_clock::now();
    const int raw = std::system((run + SPEM_FOAM + " > log.spemFoam 2>&1").c_str());
    const double wall = std::chrono::duration<double>
    (
        std::chrono::steady_clock::now() - start
    ).count();
    const int status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    const std::string log = readText(caseDir/"log.spemFoam");

    // An exit, never a crash (signal) or a hang
    ASSERT_GE(status, 0) << "spemFoam crashed:\n" << log;
    const bool stopped = status != 0;
    if (ec.stopMessage.empty())
    {
        EXPECT_FALSE(stopped) << "expected to run to endTime:\n" << log;
        EXPECT_TRUE(contains(log, "\nEnd")) << log;
    }
    else
    {
        EXPECT_TRUE(stopped) << "expected to stop:\n" << log;
        for (const std::string& part : ec.stopMessage)
        {
            EXPECT_TRUE(contains(log, part))
                << "'" << part << "' is not in the log:\n" << log;
        }
    }
    for (const std::string& part : ec.warnings)
    {
        EXPECT_TRUE(contains(log, part))
            << "warning '" << part << "' is not in the log:\n" << log;
    }

    // The particles' kernel support 2h (WendlandC2, h from the log)
    const double h = numberAfter(log, "m, h ");
    const double reach = std::isfinite(h) ? 2*h : 0;
    const stateCheck c = checkStates(caseDir, reach);
    // A stop at the start (a refused entry) writes nothing
    if (contains(log, "Starting time loop"))
    {
        EXPECT_GE(c.nStates, 2u) << "no states written";
    }
    EXPECT_EQ(c.nonFinite, 0u) << "non-finite values in the written states";
    EXPECT_EQ(c.particlesThroughWalls, 0u)
        << "fluid particles outside the tank by more than " << reach << " m";
    EXPECT_EQ(c.nodesThroughWalls, 0u)
        << "element nodes through a wall (least margin " << c.nodeMargin << " m)";

    double tip = NAN;
    if (ec.tutorial == "damBreakElasticPlate")
    {
        tip = tipMotionBefore(caseDir, 0.06);
        if (ec.plateStillBeforeImpact)
        {
            // 1e-4 m: 400 times the motion at maxCo 1, 20 times below the
            // 2 mm of the unstable maxCo 2
            EXPECT_LT(tip, 1e-4)
                << "the plate moves before the water reaches it";
        }
    }

    std::cout
        << "EXTREME " << ec.name << ": "
        << (stopped ? "stopped" : "ran to the end") << " in " << wall << " s"
        << ", " << c.nStates << " states, least particle margin "
        << c.particleMargin << " m (reach " << reach << "), least node margin "
        << c.nodeMargin << " m"
        << (std::isfinite(tip) ? ", tip motion before 0.06 s " + std::to_string(tip) + " m" : "")
        << (contains(log, machWarning) ? ", Mach warning" : "")
        << std::endl;
    if (stopped)
    {
        const std::size_t at = log.find("FATAL");
        std::cout << "    " << log.substr(at, log.find('\n', log.find('\n', at) + 1) - at)
            << std::endl;
    }
    if (!HasFailure()) fs::remove_all(tmpl);
}

const std::vector<extremeCase> cases
{
    // damBreak, method SPH (the tutorial's), nx 10 to 0.4 s: the surge hits
    // the far wall and runs up it
    {"damBreak_coarse", "damBreak", 5, 0.4, {}, {}, {}, false},
    {"damBreak_fine", "damBreak", 20, 0.4, {}, {}, {}, false},
    {"damBreak_cBy5", "damBreak", 10, 0.4, {{spemProperties, "c", "7"}}, {},
        {machWarning}, false},
    {"damBreak_cTimes10", "damBreak", 10, 0.4, {{spemProperties, "c", "350"}},
        {}, {}, false},
    {"damBreak_mu0", "damBreak", 10, 0.4, {{spemProperties, "mu", "0"}}, {},
        {}, false},
    {"damBreak_mu1", "damBreak", 10, 0.4, {{spemProperties, "mu", "1"}}, {},
        {}, false},
    {"damBreak_maxCo0.5", "damBreak", 10, 0.4, {{controlDict, "maxCo", "0.5"}},
        {}, {}, false},
    {"damBreak_maxCo1", "damBreak", 10, 0.4, {{controlDict, "maxCo", "1"}}, {},
        {}, false},
    // Above 1 refused at the start: measured before (doc/stability), 1.5
    // ran right, 2 ran to the end with the surge front 105 % off, 3 blew up
    {"damBreak_maxCo1.5", "damBreak", 10, 0.4, {{controlDict, "maxCo", "1.5"}},
        courantRefusal, {}, false},
    {"damBreak_maxCo2", "damBreak", 10, 0.4, {{controlDict, "maxCo", "2"}},
        courantRefusal, {}, false},
    {"damBreak_maxCo3", "damBreak", 10, 0.4, {{controlDict, "maxCo", "3"}},
        courantRefusal, {}, false},
    // Allowed anyway: the blow-up stops with its last good state
    {"damBreak_maxCo3_allowed", "damBreak", 10, 0.4,
        {{controlDict, "maxCo", "3"}, {controlDict, "allowMaxCoAbove1", "yes"}},
        blowUp, {courantWarning}, false},
    {"damBreak_g10", "damBreak", 10, 0.4, {{gravity, "value", "(0 -98.1 0)"}},
        {}, {machWarning}, false},

    // damBreakElasticPlate, method SPEM (the tutorial's), nx 20 to 0.25 s:
    // the surge hits the plate (about 0.1 s) and overtops it
    {"plate_coarse", "damBreakElasticPlate", 10, 0.25, {}, {}, {}, true},
    {"plate_fine", "damBreakElasticPlate", 40, 0.25, {}, {}, {}, true},
    {"plate_cBy5", "damBreakElasticPlate", 20, 0.25,
        {{spemProperties, "c", "7"}}, {}, {machWarning}, true},
    {"plate_cTimes10", "damBreakElasticPlate", 20, 0.25,
        {{spemProperties, "c", "350"}}, {}, {}, true},
    // A plate of E 1e4 folds under the surge until its elements are crushed
    // and the step collapses: a stop that says so, with the state written.
    // Single-stepped, at maxSteps ("The stable step has fallen"); with the
    // plate sub-cycled (the default: its step falls below half the
    // water's as it folds), within a sub-cycled step, when the rest of it
    // would take more sub-steps than maxSteps
    {"plate_E1e4", "damBreakElasticPlate", 20, 0.25,
        {{spemProperties, "E", "1e4"}},
        {"maxSteps", "an element is crushed", "region plate",
         "has been written"}, {}, true},
    // The stiff plate sets a step of 3e-6 s: to just after the impact
    {"plate_E1e9", "damBreakElasticPlate", 20, 0.15,
        {{spemProperties, "E", "1e9"}}, {}, {}, true},
    {"plate_mu0", "damBreakElasticPlate", 20, 0.25,
        {{spemProperties, "mu", "0"}}, {}, {}, true},
    {"plate_mu1", "damBreakElasticPlate", 20, 0.25,
        {{spemProperties, "mu", "1"}}, {}, {}, true},
    {"plate_maxCo0.5", "damBreakElasticPlate", 20, 0.25,
        {{controlDict, "maxCo", "0.5"}}, {}, {}, true},
    {"plate_maxCo1", "damBreakElasticPlate", 20, 0.25,
        {{controlDict, "maxCo", "1"}}, {}, {}, true},
    // Above 1 refused at the start: measured before, at 1.5 the plate
    // moved 6 mm before the water reached it and particles were thrown
    // 3.6 m high, both without a stop; at 3 it blew up
    {"plate_maxCo1.5", "damBreakElasticPlate", 20, 0.25,
        {{controlDict, "maxCo", "1.5"}}, courantRefusal, {}, false},
    {"plate_maxCo2", "damBreakElasticPlate", 20, 0.25,
        {{controlDict, "maxCo", "2"}}, courantRefusal, {}, false},
    {"plate_maxCo3", "damBreakElasticPlate", 20, 0.25,
        {{controlDict, "maxCo", "3"}}, courantRefusal, {}, false},
    // Ten times the gravity: the surge (Mach 0.3) splashes over the side
    // wall, which stops the run (tank leaving stop, the default) when the
    // splash comes down beside the tank: at 0.297 s since the plate's a_w
    // is smoothed (at 0.25 s the splash is still in the air, up to 2.9 m;
    // with the raw a_w it fell out before 0.25 s), so run to 0.5 s
    {"plate_g10", "damBreakElasticPlate", 20, 0.5,
        {{gravity, "value", "(0 -98.1 0)"}},
        {"outside the tank", "close it with walls", "The last good state"},
        {machWarning}, false},
};

INSTANTIATE_TEST_SUITE_P
(
    tutorials,
    Extremes,
    ::testing::ValuesIn(cases),
    [](const ::testing::TestParamInfo<extremeCase>& info)
    {
        std::string name = info.param.name;
        std::replace(name.begin(), name.end(), '.', '_');
        return name;
    }
);

} // End anonymous namespace
