/*---------------------------------------------------------------------------*\
Description
    spemStudy (bin/spemStudy) end to end: a two-run study of damBreak (SPH
    and SPEM, nx 5, 0.1 s, each with an entry of its own) writes a CSV
    whose steps, counts and CPU times are the runs' own (read back from
    their logs), resumes without redoing a finished run, and its error
    measures give zero on a run compared with itself and the right value
    on synthetic curves.

\*---------------------------------------------------------------------------*/

#include "testFiles.H"
#include "tutorialCases.H"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;
using testFiles::readText;

namespace
{

// The system's python3 has the Debian matplotlib (bin/installDependencies)
const std::string python = "/usr/bin/python3";
const std::string spemStudy = std::string(SPEM_PROJECT_DIR) + "/bin/spemStudy";
const std::string errorsModule = std::string(SPEM_PROJECT_DIR) + "/bin/tools";

fs::path newFolder(const std::string& prefix)
{
    std::string tmpl = (fs::temp_directory_path()/(prefix + "-XXXXXX")).string();
    if (!::mkdtemp(tmpl.data())) return {};
    return tmpl;
}

//- Rows of a CSV file as column name -> text
std::vector<std::map<std::string, std::string>> readCsv(const fs::path& file)
{
    std::ifstream is(file);
    std::string line;
    std::vector<std::string> header;
    std::vector<std::map<std::string, std::string>> rows;
    // Cells split at commas outside double quotes ("" is a quote)
    auto split = [](const std::string& l)
    {
        std::vector<std::string> cells(1);
        bool quoted = false;
        for (std::size_t i = 0; i < l.size(); ++i)
        {
            const char c = l[i];
            if (c == '"')
            {
                if (quoted && i + 1 < l.size() && l[i + 1] == '"')
                {
                    cells.back() += '"';
                    ++i;
                }
                else
                {
                    quoted = !quoted;
                }
            }
            else if (c == ',' && !quoted) cells.emplace_back();
            else if (c != '\r') cells.back() += c;
        }
        return cells;
    };
    if (std::getline(is, line)) header = split(line);
    while (std::getline(is, line))
    {
        const std::vector<std::string> cells = split(line);
        std::map<std::string, std::string> row;
        for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i)
        {
            row[header[i]] = cells[i];
        }
        rows.push_back(row);
    }
    return rows;
}

//- The last match of re's first group in text
std::string lastMatch(const std::string& text, const std::regex& re)
{
    std::string last;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re);
         it != std::sregex_iterator(); ++it)
    {
        last = (*it)[1].str();
    }
    return last;
}

//- The value of a dictionary entry (a/b in a sub-dictionary) as
//  foamDictionary prints it, empty when the entry is missing
std::string foamEntry(const fs::path& file, const std::string& entry)
{
    const fs::path out = file.string() + ".entry";
    const std::string cmd =
        "foamDictionary -entry " + entry + " -value '" + file.string()
      + "' > '" + out.string() + "' 2> /dev/null";
    std::string value = std::system(cmd.c_str()) == 0 ? readText(out) : "";
    fs::remove(out);
    while (!value.empty() && std::isspace(value.back())) value.pop_back();
    return value;
}

int runIn(const fs::path& dir, const std::string& command, const std::string& log)
{
    const std::string cmd =
        "cd '" + dir.string() + "' && " + command + " > '" + log + "' 2>&1";
    return std::system(cmd.c_str());
}


TEST(SpemStudy, twoRunStudyWritesTheRunsOwnNumbersAndResumes)
{
    const fs::path root = newFolder("spemStudyTest");
    ASSERT_FALSE(root.empty());
    const fs::path caseDir = tutorialCases::copyTutorial
    (
        "damBreak", (root.filename()/"damBreak").string()
    );
    fs::create_directory_symlink
    (
        fs::path(SPEM_PROJECT_DIR)/"tutorials"/"damBreak"/"referenceData",
        caseDir/"referenceData"
    );
    std::ofstream(caseDir/"system"/"spemStudyDict")
        << "FoamFile { version 2.0; format ascii; class dictionary;"
           " object spemStudyDict; }\n"
           "methods     (SPH SPEM);\n"
           "resolutions (5);\n"
           "endTime     0.1;\n"
           "methodResolutions { SPEM (4); }\n"
           "methodEntries\n{\n"
           "    SPH  (\"system/spemSchemes\" \"sph/densityDiffusion\" 0.05);\n"
           "    SPEM (\"system/spemSchemes\" \"conversion/minInteriorAngle\" 25);\n"
           "}\n";

    ASSERT_EQ(runIn(caseDir, python + " " + spemStudy, "log.spemStudy"), 0)
        << readText(caseDir/"log.spemStudy");
    const std::string first = readText(caseDir/"log.spemStudy");
    EXPECT_NE(first.find("2 of 2 runs done"), std::string::npos) << first;
    for (const char* f : {"trade.csv", "trade.md", "trade.png"})
    {
        EXPECT_TRUE(fs::exists(caseDir/"study"/f)) << f;
    }

    const auto rows = readCsv(caseDir/"study"/"trade.csv");
    ASSERT_EQ(rows.size(), 2u);
    for (const auto& row : rows)
    {
        SCOPED_TRACE(row.at("name"));
        const fs::path runDir = caseDir/"study"/row.at("name");
        const std::string log = readText(runDir/"log.spemFoam");
        EXPECT_EQ(row.at("ranToEnd"), "True");
        EXPECT_EQ
        (
            row.at("steps"), lastMatch(log, std::regex(", step (\\d+)\n"))
        );
        EXPECT_EQ
        (
            row.at("particles"),
            lastMatch(log, std::regex("nodes = \\d+, particles = (\\d+)"))
        );
        EXPECT_EQ
        (
            row.at("elements"), lastMatch(log, std::regex("elements = (\\d+)"))
        );
        // The method the run was set to, in the copy's dictionary
        EXPECT_NE
        (
            readText(runDir/"system"/"spemSchemes").find
            (
                "method          " + row.at("method") + ";"
            ),
            std::string::npos
        );
        // methodResolutions: SPEM at its own nx, SPH at the study's
        const std::string nx = row.at("method") == "SPH" ? "5" : "4";
        EXPECT_EQ(row.at("name"), row.at("method") + "_nx" + nx);
        EXPECT_EQ(row.at("nx"), nx);
        EXPECT_EQ(foamEntry(runDir/"system"/"blockMeshDict", "nx"), nx);
        // methodEntries: each method's entries in its own runs only, the
        // sub-dictionary the tutorial lacks added
        const bool sph = row.at("method") == "SPH";
        EXPECT_EQ
        (
            foamEntry(runDir/"system"/"spemSchemes", "sph/densityDiffusion"),
            sph ? "0.05" : "0.1"
        );
        EXPECT_EQ
        (
            foamEntry
            (
                runDir/"system"/"spemSchemes", "conversion/minInteriorAngle"
            ),
            sph ? "" : "25"
        );
        // CPU time of spemFoam from wait4 against the solver's own
        // ExecutionTime (its CPU clock at the last log entry: the end of
        // the run, less the final write and exit)
        const double cpu = std::stod(row.at("solverCpuTime"));
        const double own = std::stod
        (
            lastMatch(log, std::regex("ExecutionTime = ([0-9.eE+-]+) s"))
        );
        EXPECT_GE(cpu, own - 0.01);
        EXPECT_LE(cpu, own + 0.5 + 0.2*own);
        // The error is the measure of the tutorial: a number
        EXPECT_FALSE(row.at("error").empty());
        EXPECT_GT(std::stod(row.at("error")), 0);
    }

    // Again: both runs are kept, not redone (their results untouched)
    const auto stamp = fs::last_write_time(caseDir/"study"/"SPH_nx5"/"result.json");
    ASSERT_EQ(runIn(caseDir, python + " " + spemStudy, "log.spemStudy.2"), 0);
    const std::string second = readText(caseDir/"log.spemStudy.2");
    EXPECT_NE(second.find("SPH_nx5 done before, kept"), std::string::npos) << second;
    EXPECT_NE(second.find("SPEM_nx4 done before, kept"), std::string::npos) << second;
    EXPECT_EQ(second.find("running (SPH"), std::string::npos) << second;
    EXPECT_EQ
    (
        fs::last_write_time(caseDir/"study"/"SPH_nx5"/"result.json"), stamp
    );
    if (!HasFailure()) fs::remove_all(root);
}


TEST(SpemStudy, stabilityMapRecordsWhichRunsEndAndWhichStopWithWhatMessage)
{
    const fs::path root = newFolder("spemStudyMap");
    ASSERT_FALSE(root.empty());
    const fs::path caseDir = tutorialCases::copyTutorial
    (
        "damBreak", (root.filename()/"damBreak").string()
    );
    testFiles::replaceEntry(caseDir/"system"/"blockMeshDict", "nx", "5");
    // maxCo 20 to blow up in the run, not to be refused at the start
    std::ofstream(caseDir/"system"/"controlDict", std::ios::app)
        << "\nallowMaxCoAbove1 yes;\n";
    std::ofstream(caseDir/"system"/"spemStudyDict")
        << "FoamFile { version 2.0; format ascii; class dictionary;"
           " object spemStudyDict; }\n"
           "endTime     0.4;\n"
           "error       finest;\n"
           "parameter { file system/controlDict; entry maxCo; values (1 20); }\n";
    ASSERT_EQ(runIn(caseDir, python + " " + spemStudy, "log.spemStudy"), 0)
        << readText(caseDir/"log.spemStudy");
    const auto rows = readCsv(caseDir/"study"/"trade.csv");
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].at("name"), "maxCo_1");
    EXPECT_EQ(rows[0].at("ranToEnd"), "True");
    EXPECT_EQ(rows[0].at("silentFailure"), "");
    EXPECT_EQ(rows[1].at("name"), "maxCo_20");
    EXPECT_EQ(rows[1].at("ranToEnd"), "False");
    EXPECT_EQ(rows[1].at("failedIn"), "spemFoam");
    // The solver's own first line of the stop
    const std::string log = readText(caseDir/"study"/"maxCo_20"/"log.spemFoam");
    EXPECT_NE(log.find(rows[1].at("message")), std::string::npos)
        << rows[1].at("message");
    EXPECT_NE(rows[1].at("message").find("Run stopped"), std::string::npos)
        << rows[1].at("message");
    if (!HasFailure()) fs::remove_all(root);
}


//- Value printed by a python snippet using the error module
double pythonValue(const fs::path& dir, const std::string& code)
{
    const std::string cmd =
        "cd '" + dir.string() + "' && " + python + " -c \"import sys; "
        "sys.path.insert(0, '" + errorsModule + "'); import spemStudyErrors "
        "as e; " + code + "\" > value.txt 2>&1";
    if (std::system(cmd.c_str()) != 0)
    {
        ADD_FAILURE() << readText(dir/"value.txt");
        return NAN;
    }
    return std::stod(readText(dir/"value.txt"));
}

//- A postProcessing table: rows of (t, values...)
void writeTable
(
    const fs::path& caseDir,
    const std::string& name,
    const std::vector<std::vector<double>>& rows
)
{
    const fs::path dir = caseDir/"postProcessing"/name/"0";
    fs::create_directories(dir);
    std::ofstream os(dir/(name + ".dat"));
    os.precision(17);
    os << "# Time\tvalues\n";
    for (const auto& r : rows)
    {
        for (std::size_t i = 0; i < r.size(); ++i) os << (i ? "\t" : "") << r[i];
        os << '\n';
    }
}


TEST(SpemStudy, errorMeasuresGiveZeroOnItselfAndTheRightValueOnSyntheticCurves)
{
    const fs::path root = newFolder("spemStudyErrors");
    ASSERT_FALSE(root.empty());

    // A curve compared with itself: 0
    writeTable(root/"a", "plateTip", {{0, 0, 0}, {0.1, 0.01, 0}, {0.2, 0.03, 0}});
    EXPECT_EQ(pythonValue(root, "print(e.finest('a', 'a')[0])"), 0);

    // Twice the finest run's curve: relative RMS difference 1
    writeTable(root/"b", "plateTip", {{0, 0, 0}, {0.1, 0.02, 0}, {0.2, 0.06, 0}});
    EXPECT_NEAR(pythonValue(root, "print(e.finest('b', 'a')[0])"), 1, 1e-12);

    // The tip displacement 1 mm above Ryzhakov et al. at each of its times:
    // RMS 1 mm
    const fs::path ref = fs::path(SPEM_PROJECT_DIR)/"tutorials"
        /"damBreakElasticPlate"/"referenceData";
    fs::create_directories(root/"c");
    fs::create_directory_symlink(ref, root/"c"/"referenceData");
    std::vector<std::vector<double>> tip;
    for (const auto& r : tutorialCases::readTable(ref/"Ryzhakov2010_tipDisplacement.dat"))
    {
        tip.push_back({r[0], r[1] + 1e-3, 0});
    }
    ASSERT_GT(tip.size(), 5u);
    writeTable(root/"c", "plateTip", tip);
    EXPECT_NEAR(pythonValue(root, "print(e.plateTip('c')[0])"), 1e-3, 1e-12);

    // The surge front 10 % ahead of Martin & Moyce at each of their times
    // (Z = x/a, T = t sqrt(2 g/a)): largest relative error 0.1
    const fs::path surgeRef = fs::path(SPEM_PROJECT_DIR)/"tutorials"
        /"damBreak"/"referenceData";
    fs::create_directories(root/"d");
    fs::create_directory_symlink(surgeRef, root/"d"/"referenceData");
    const double a = 0.146, g = 9.81;
    std::vector<std::vector<double>> front;
    for (const auto& r : tutorialCases::readTable(surgeRef/"MartinMoyce1952_surgeFront.dat"))
    {
        front.push_back({r[0]/std::sqrt(2*g/a), 1.1*r[1]*a, 0.2});
    }
    writeTable(root/"d", "surgeFront", front);
    EXPECT_NEAR(pythonValue(root, "print(e.surgeFront('d')[0])"), 0.1, 1e-9);

    // Tank probes at y = 0 and 0.25 m (H 0.5 m): over the last 10 % of
    // the run the first reads rho0 g H plus 1 % of it, the second exactly
    // rho0 g (H - y): largest error 0.01
    {
        const fs::path dir = root/"e"/"postProcessing"/"probes"/"0";
        fs::create_directories(dir);
        std::ofstream os(dir/"probes.dat");
        os.precision(17);
        const double scale = 1000*9.81*0.5;
        os  << "# Probe 0 (0.25 0)\n# Probe 1 (0.25 0.25)\n"
            << "#  Probe 0 1\n# Time\n";
        for (int k = 0; k <= 10; ++k)
        {
            // Far from the end the first probe reads something else
            const double p0 = k >= 9 ? 1.01*scale : 0.8*scale;
            os  << 0.1*k << '\t' << p0 << '\t' << 0.5*scale << '\n';
        }
    }
    EXPECT_NEAR
    (
        pythonValue(root, "print(e.hydrostaticPressure('e')[0])"), 0.01, 1e-12
    );

    // A body's vertical force 10 % above the reference run's at every
    // time: relative RMS difference 0.1; the x column is not read
    writeTable(root/"f", "body", {{0, 0, 0, 0, 0, 0, 0, 5, 100, 0}, {0.1, 0, 0, 0, 0, 0, 0, 5, 200, 0}});
    writeTable(root/"g", "body", {{0, 9, 0, 0, 0, 0, 0, 7, 110, 0}, {0.1, 9, 0, 0, 0, 0, 0, 7, 220, 0}});
    for (const char* run : {"f", "g"})
    {
        // The rigidBodyState header names the columns
        const fs::path file = root/run/"postProcessing"/"body"/"0"/"body.dat";
        std::string text = readText(file);
        text.replace(0, text.find('\n'), "# Time\tx\ty\tangle\tu\tv\tomega\tFx\tFy\tMz");
        std::ofstream(file) << text;
    }
    EXPECT_NEAR(pythonValue(root, "print(e.bodyForce('g', 'f')[0])"), 0.1, 1e-12);
    EXPECT_EQ(pythonValue(root, "print(e.bodyForce('f', 'f')[0])"), 0);

    // The free surface (surfaceProfile, one table per write time) 0.1 m
    // above the reference's flat one at t = 1 and 0.3 m at t = 2, at each
    // of the reference's x; a time the reference lacks is not read: RMS
    // sqrt((3 0.1^2 + 3 0.3^2)/6) = sqrt(0.05)
    for (const auto& [run, t, y] : std::vector<std::tuple<std::string, std::string, double>>
        {{"h", "1", 0}, {"h", "2", 0}, {"i", "1", 0.1}, {"i", "2", 0.3}, {"i", "3", 7}})
    {
        const fs::path dir = root/run/"postProcessing"/"surfaceProfile"/"0"/t;
        fs::create_directories(dir);
        std::ofstream os(dir/"surfaceProfile.dat");
        os  << "# Free surface\n# x\ty\n";
        for (const double x : {-1.0, 0.0, 1.0}) os << x << '\t' << y << '\n';
    }
    EXPECT_NEAR
    (
        pythonValue(root, "print(e.surfaceHeight('i', 'h')[0])"),
        std::sqrt(0.05), 1e-12
    );
    EXPECT_EQ(pythonValue(root, "print(e.surfaceHeight('h', 'h')[0])"), 0);

    // The plate's mid-span deflection 1.1 times the shear-corrected value
    // of its referenceData over the last 10 % of the run, half of it
    // before: error 0.1
    {
        const fs::path plateRef = fs::path(SPEM_PROJECT_DIR)/"tutorials"
            /"hydrostaticElasticPlate"/"referenceData";
        fs::create_directories(root/"j");
        fs::create_directory_symlink(plateRef, root/"j"/"referenceData");
        double wT = 0;
        std::istringstream is(readText(plateRef/"midSpanDeflection.dat"));
        std::string key;
        for (std::string line; std::getline(is, line); )
        {
            std::istringstream ls(line);
            double v;
            if (ls >> key >> v && key == "Dy_Timoshenko") wT = v;
        }
        ASSERT_LT(wT, 0);
        std::vector<std::vector<double>> dy;
        for (int k = 0; k <= 20; ++k)
        {
            dy.push_back({0.01*k, 0, k >= 18 ? 1.1*wT : 0.5*wT});
        }
        writeTable(root/"j", "midSpan", dy);
    }
    EXPECT_NEAR(pythonValue(root, "print(e.midSpan('j')[0])"), 0.1, 1e-12);

    if (!HasFailure()) fs::remove_all(root);
}

} // End anonymous namespace
