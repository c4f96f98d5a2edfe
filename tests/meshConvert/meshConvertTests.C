/*---------------------------------------------------------------------------*\
Description
    Tests of spemMeshConvert. Each test copies a small case from cases/ into
    a fresh temporary folder, runs Debian's blockMesh and our spemMeshConvert
    on it as separate programs (as a user would), and reads the written
    constant/spemMesh back with triMesh::read.

    cases/twoZone          1 x 0.5 water box (10 x 10 cells) on a 1 x 0.1
                           plate strip (10 x 2 cells); all cells 0.1 x 0.05
    cases/graded           unit square, 8 x 8 cells, simpleGrading (4 0.25 1),
                           no spemMeshConvertDict (defaults)
    cases/threeD           unit cube, 2 x 2 x 2 cells, no empty patches
    cases/cellWithoutZone  two 2 x 2 blocks, one without a zone
    cases/noZones          one block without a zone: no cellZones at all

    The temporary folder is removed when a test passes and kept (its path
    printed) when it fails, with log.blockMesh and log.spemMeshConvert.

\*---------------------------------------------------------------------------*/

#include "Time.H"
#include "triMesh.H"

#include "testFiles.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>

#ifndef SPEM_MESH_CONVERT
#define SPEM_MESH_CONVERT "spemMeshConvert"
#endif

namespace fs = std::filesystem;

namespace
{

// Geometry of cases/twoZone (see its blockMeshDict)
const double cellWidth = 0.1;     // x
const double cellHeight = 0.05;   // y
const int nCellsX = 10;
const int nCellsY = 12;           // 2 plate + 10 water
const int nTwoZoneCells = nCellsX*nCellsY;
const int nTwoZonePoints = (nCellsX + 1)*(nCellsY + 1);  // front plane
const double plateArea = 1*0.1;
const double waterArea = 1*0.5;
const double twoZoneArea = plateArea + waterArea;

const double areaTolerance = 1e-12;   // relative


//- Length of a boundary segment of the mesh
double segmentLength(const Foam::triMesh& mesh, const Foam::label s)
{
    const auto& p = mesh.points();
    const auto a = mesh.segments()[2*s], b = mesh.segments()[2*s + 1];
    return std::hypot(p[2*b] - p[2*a], p[2*b + 1] - p[2*a + 1]);
}


//- Whether the mesh has an edge between nodes a and b
bool hasEdge(const Foam::triMesh& mesh, Foam::label a, Foam::label b)
{
    if (a > b) std::swap(a, b);
    const auto& e = mesh.edges();
    for (std::size_t i = 0; i < e.size(); i += 2)
    {
        if (e[i] == a && e[i + 1] == b) return true;
    }
    return false;
}


using testFiles::readText;


//- Write an OpenFOAM dictionary with the standard FoamFile header
void writeDictionary
(
    const fs::path& file,
    const std::string& location,
    const std::string& body
)
{
    std::ofstream os(file);
    os  << "FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
        << "    class       dictionary;\n    location    \"" << location
        << "\";\n    object      " << file.filename().string() << ";\n}\n\n"
        << body << "\n";
}


//- Fixture: a case copied to a fresh temporary folder
class MeshConvert : public ::testing::Test
{
protected:

    fs::path caseDir_;

    void TearDown() override
    {
        if (caseDir_.empty()) return;
        if (HasFailure())
        {
            std::cout << "Case kept for inspection: " << caseDir_ << std::endl;
        }
        else
        {
            std::error_code ec;
            fs::remove_all(caseDir_.parent_path(), ec);
        }
    }

    //- Copy cases/<name> to <new temporary folder>/<name>
    void copyCase(const std::string& name)
    {
        std::string tmpl =
            (fs::temp_directory_path()/"spemMeshConvertTest-XXXXXX").string();
        ASSERT_NE(::mkdtemp(tmpl.data()), nullptr) << "cannot make " << tmpl;
        caseDir_ = fs::path(tmpl)/name;
        fs::copy
        (
            fs::path(SPEM_TEST_SOURCE_DIR)/"cases"/name,
            caseDir_,
            fs::copy_options::recursive
        );
    }

    //- Run a program on the case, output to log.<program>; exit status.
    //  spemMeshConvert is the one built with these tests, blockMesh the
    //  one on PATH
    int runOnCase(const std::string& program)
    {
        const fs::path log = caseDir_/("log." + program);
        const std::string executable =
            program == "spemMeshConvert" ? SPEM_MESH_CONVERT : program;
        const std::string cmd =
            "'" + executable + "' -case '" + caseDir_.string() + "' > '"
          + log.string() + "' 2>&1";
        const int status = std::system(cmd.c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }

    std::string log(const std::string& program) const
    {
        return readText(caseDir_/("log." + program));
    }

    //- Copy, blockMesh and convert with the given split (empty: the case's
    //  own settings). Fatal test failure if a program fails.
    void convert(const std::string& name, const std::string& split = "")
    {
        copyCase(name);
        if (HasFatalFailure()) return;
        if (!split.empty())
        {
            writeDictionary
            (
                caseDir_/"system"/"spemMeshConvertDict",
                "system",
                "split   " + split + ";"
            );
        }
        ASSERT_EQ(runOnCase("blockMesh"), 0) << log("blockMesh");
        ASSERT_EQ(runOnCase("spemMeshConvert"), 0)
            << log("spemMeshConvert");
    }

    //- Copy and blockMesh, then expect spemMeshConvert to fail; its log
    std::string convertExpectingFailure()
    {
        EXPECT_EQ(runOnCase("blockMesh"), 0) << log("blockMesh");
        const int status = runOnCase("spemMeshConvert");
        const std::string text = log("spemMeshConvert");
        EXPECT_NE(status, 0) << "spemMeshConvert accepted the case:\n" << text;
        EXPECT_EQ(text.find("\nEnd"), std::string::npos) << text;
        return text;
    }

    //- Read constant/spemMesh of the case
    Foam::triMesh readMesh() const
    {
        Foam::FatalError.throwExceptions();
        Foam::FatalIOError.throwExceptions();
        const Foam::Time runTime
        (
            Foam::Time::controlDictName,
            Foam::fileName(caseDir_.parent_path().string()),
            Foam::fileName(caseDir_.filename().string())
        );
        return Foam::triMesh::read(runTime);
    }
};


//- Node label of each twoZone grid position (i, j) = (x/0.1, y/0.05)
std::map<std::pair<int, int>, Foam::label> twoZoneGridNodes
(
    const Foam::triMesh& mesh
)
{
    std::map<std::pair<int, int>, Foam::label> nodeAt;
    const auto& p = mesh.points();
    for (Foam::label n = 0; n < mesh.nPoints(); ++n)
    {
        const int i = int(std::lround(p[2*n]/cellWidth));
        const int j = int(std::lround(p[2*n + 1]/cellHeight));
        EXPECT_NEAR(p[2*n], i*cellWidth, 1e-12);
        EXPECT_NEAR(p[2*n + 1], j*cellHeight, 1e-12);
        nodeAt[{i, j}] = n;
    }
    EXPECT_EQ(Foam::label(nodeAt.size()), mesh.nPoints())
        << "two nodes at the same position";
    return nodeAt;
}


//- Diagonal of each twoZone cell (i, j): +1 for "/", -1 for "\", 0 for
//  none or both (an error)
std::vector<std::vector<int>> twoZoneDiagonals(const Foam::triMesh& mesh)
{
    auto nodeAt = twoZoneGridNodes(mesh);
    std::vector<std::vector<int>> diagonal(nCellsX, std::vector<int>(nCellsY));
    for (int i = 0; i < nCellsX; ++i)
    {
        for (int j = 0; j < nCellsY; ++j)
        {
            const bool slash =
                hasEdge(mesh, nodeAt[{i, j}], nodeAt[{i + 1, j + 1}]);
            const bool backslash =
                hasEdge(mesh, nodeAt[{i + 1, j}], nodeAt[{i, j + 1}]);
            diagonal[i][j] = (slash && !backslash) ? 1
                           : (backslash && !slash) ? -1 : 0;
            EXPECT_NE(diagonal[i][j], 0)
                << "cell (" << i << ", " << j << ") has "
                << (slash ? "both diagonals" : "no diagonal");
        }
    }
    return diagonal;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Valid meshes  * * * * * * * * * * * * * * //

TEST_F(MeshConvert, alternatingSplitGivesTwoTrianglesPerCell)
{
    convert("twoZone", "alternating");
    if (HasFatalFailure()) return;
    const Foam::triMesh mesh(readMesh());

    EXPECT_EQ(mesh.nTriangles(), 2*nTwoZoneCells);
    EXPECT_EQ(mesh.nPoints(), nTwoZonePoints) << "front-plane nodes only";
    EXPECT_NE(log("spemMeshConvert").find("\nEnd"), std::string::npos);
}


TEST_F(MeshConvert, crossSplitAddsCentroidNodeAndFourTrianglesPerCell)
{
    convert("twoZone", "cross");
    if (HasFatalFailure()) return;
    const Foam::triMesh mesh(readMesh());

    EXPECT_EQ(mesh.nTriangles(), 4*nTwoZoneCells);
    EXPECT_EQ(mesh.nPoints(), nTwoZonePoints + nTwoZoneCells);

    // Every node is either a grid point (0.1 i, 0.05 j) or a cell centre
    // (0.1 i + 0.05, 0.05 j + 0.025), each cell centre exactly once
    const auto& p = mesh.points();
    std::set<std::pair<long, long>> gridPoints, centres;
    for (Foam::label n = 0; n < mesh.nPoints(); ++n)
    {
        const double i = p[2*n]/cellWidth;
        const double j = p[2*n + 1]/cellHeight;
        if (std::abs(i - std::round(i)) < 1e-9)
        {
            EXPECT_NEAR(j, std::round(j), 1e-9) << "node " << n;
            gridPoints.insert({std::lround(i), std::lround(j)});
        }
        else
        {
            EXPECT_NEAR(i - 0.5, std::round(i - 0.5), 1e-9) << "node " << n;
            EXPECT_NEAR(j - 0.5, std::round(j - 0.5), 1e-9) << "node " << n;
            centres.insert({std::lround(i - 0.5), std::lround(j - 0.5)});
        }
    }
    EXPECT_EQ(long(gridPoints.size()), long(nTwoZonePoints));
    EXPECT_EQ(long(centres.size()), long(nTwoZoneCells));
}


TEST_F(MeshConvert, regionSplitOverridesSplitForOneZone)
{
    // The plate (2 rows of cells) split in four, the water in two
    convert("twoZone", "alternating; regionSplit { plate cross; }");
    if (HasFatalFailure()) return;
    const Foam::triMesh mesh(readMesh());

    const int nPlateCells = 2*nCellsX;
    const int nWaterCells = nTwoZoneCells - nPlateCells;
    EXPECT_EQ(mesh.nTriangles(), 4*nPlateCells + 2*nWaterCells);
    EXPECT_EQ(mesh.nPoints(), nTwoZonePoints + nPlateCells);

    const Foam::label plate = mesh.findRegion("plate");
    const Foam::label water = mesh.findRegion("water");
    int nPlate = 0, nWater = 0;
    for (Foam::label t = 0; t < mesh.nTriangles(); ++t)
    {
        if (mesh.triangleRegion()[t] == plate) ++nPlate;
        if (mesh.triangleRegion()[t] == water) ++nWater;
    }
    EXPECT_EQ(nPlate, 4*nPlateCells);
    EXPECT_EQ(nWater, 2*nWaterCells);
    EXPECT_NEAR(mesh.regionArea(plate), plateArea, areaTolerance*plateArea);
    EXPECT_NEAR(mesh.regionArea(water), waterArea, areaTolerance*waterArea);
}


TEST_F(MeshConvert, areasSumToDomainArea)
{
    for (const std::string split : {"alternating", "cross", "right", "left"})
    {
        SCOPED_TRACE("split " + split);
        convert("twoZone", split);
        if (HasFatalFailure()) return;
        const Foam::triMesh mesh(readMesh());

        double sum = 0;
        for (Foam::label t = 0; t < mesh.nTriangles(); ++t)
        {
            sum += mesh.triangleArea(t);
        }
        EXPECT_NEAR(sum, twoZoneArea, areaTolerance*twoZoneArea);
        if (HasFailure()) return;
        fs::remove_all(caseDir_.parent_path());
    }
}


TEST_F(MeshConvert, regionAreasMatchZoneAreas)
{
    convert("twoZone");
    if (HasFatalFailure()) return;
    const Foam::triMesh mesh(readMesh());

    const Foam::label water = mesh.findRegion("water");
    const Foam::label plate = mesh.findRegion("plate");
    ASSERT_GE(water, 0);
    ASSERT_GE(plate, 0);
    EXPECT_NEAR(mesh.regionArea(water), waterArea, areaTolerance*waterArea);
    EXPECT_NEAR(mesh.regionArea(plate), plateArea, areaTolerance*plateArea);

    // Each triangle's region is that of the cell it came from: the plate
    // is y < 0.1
    const auto& p = mesh.points();
    const auto& tri = mesh.triangles();
    for (Foam::label t = 0; t < mesh.nTriangles(); ++t)
    {
        const double yc =
            (p[2*tri[3*t] + 1] + p[2*tri[3*t + 1] + 1] + p[2*tri[3*t + 2] + 1])/3;
        EXPECT_EQ(mesh.triangleRegion()[t], yc < 0.1 ? plate : water)
            << "triangle " << t << " at y = " << yc;
    }
}


TEST_F(MeshConvert, regionNamesAreZoneNames)
{
    convert("twoZone");
    if (HasFatalFailure()) return;
    const Foam::triMesh mesh(readMesh());

    ASSERT_EQ(mesh.nRegions(), 2);
    // blockMesh makes the zones in the order of the blocks
    EXPECT_EQ(mesh.regionNames()[0], "plate");
    EXPECT_EQ(mesh.regionNames()[1], "water");
}


TEST_F(MeshConvert, patchesKeepNamesAndLengthsWithoutEmpty)
{
    convert("twoZone");
    if (HasFatalFailure()) return;
    const Foam::triMesh mesh(readMesh());

    // Non-empty patches in polyMesh (= blockMeshDict) order, with their
    // lengths; frontAndBack (empty) is dropped
    const std::vector<std::pair<std::string, double>> expected
    {
        {"plateBottom", 1.0}, {"plateEnds", 0.2}, {"walls", 1.0}, {"top", 1.0}
    };
    ASSERT_EQ(mesh.nPatches(), Foam::label(expected.size()));
    std::vector<double> length(mesh.nPatches(), 0);
    for (Foam::label s = 0; s < mesh.nSegments(); ++s)
    {
        length[mesh.segmentPatch()[s]] += segmentLength(mesh, s);
    }
    for (std::size_t i = 0; i < expected.size(); ++i)
    {
        EXPECT_EQ(mesh.patchNames()[i], expected[i].first);
        EXPECT_NEAR(length[i], expected[i].second, 1e-12)
            << "patch " << expected[i].first;
    }
    EXPECT_EQ(mesh.findPatch("frontAndBack"), -1);
    EXPECT_EQ(mesh.nSegments(), 2*nCellsX + 2*nCellsY);
}


TEST_F(MeshConvert, alternatingDiagonalsDifferBetweenNeighbours)
{
    convert("twoZone", "alternating");
    if (HasFatalFailure()) return;
    const Foam::triMesh mesh(readMesh());
    const auto diagonal = twoZoneDiagonals(mesh);

    for (int i = 0; i < nCellsX; ++i)
    {
        for (int j = 0; j < nCellsY; ++j)
        {
            if (i + 1 < nCellsX)
            {
                EXPECT_NE(diagonal[i][j], diagonal[i + 1][j])
                    << "cells (" << i << ", " << j << ") and ("
                    << i + 1 << ", " << j << ")";
            }
            if (j + 1 < nCellsY)
            {
                EXPECT_NE(diagonal[i][j], diagonal[i][j + 1])
                    << "cells (" << i << ", " << j << ") and ("
                    << i << ", " << j + 1 << ")";
            }
        }
    }
}


TEST_F(MeshConvert, rightAndLeftSplitsUseOneDiagonalEverywhere)
{
    for (const auto& [split, direction] :
        std::vector<std::pair<std::string, int>>{{"right", 1}, {"left", -1}})
    {
        SCOPED_TRACE("split " + split);
        convert("twoZone", split);
        if (HasFatalFailure()) return;
        const auto diagonal = twoZoneDiagonals(readMesh());
        for (int i = 0; i < nCellsX; ++i)
        {
            for (int j = 0; j < nCellsY; ++j)
            {
                EXPECT_EQ(diagonal[i][j], direction)
                    << "cell (" << i << ", " << j << ")";
            }
        }
        if (HasFailure()) return;
        fs::remove_all(caseDir_.parent_path());
    }
}


TEST_F(MeshConvert, gradedMeshKeepsGradingAreaAndPositiveTriangles)
{
    convert("graded");    // no spemMeshConvertDict: defaults
    if (HasFatalFailure()) return;
    const Foam::triMesh mesh(readMesh());
    const int n = 8;

    EXPECT_EQ(mesh.nTriangles(), 2*n*n) << "default split is alternating";
    EXPECT_NE(log("spemMeshConvert").find("split alternating"),
        std::string::npos);

    double sum = 0;
    for (Foam::label t = 0; t < mesh.nTriangles(); ++t)
    {
        EXPECT_GT(mesh.triangleArea(t), 0) << "triangle " << t;
        sum += mesh.triangleArea(t);
    }
    EXPECT_NEAR(sum, 1.0, areaTolerance);

    // The grading survives: last/first cell size is 4 in x, 1/4 in y.
    // (blockMesh's positions of one grid line differ by round-off between
    // rows, hence the tolerance when collecting the distinct values)
    auto gridLines = [&mesh](const int component)
    {
        std::vector<double> v;
        for (Foam::label i = 0; i < mesh.nPoints(); ++i)
        {
            v.push_back(mesh.points()[2*i + component]);
        }
        std::sort(v.begin(), v.end());
        v.erase
        (
            std::unique
            (
                v.begin(), v.end(),
                [](double a, double b) { return b - a < 1e-12; }
            ),
            v.end()
        );
        return v;
    };
    const std::vector<double> x = gridLines(0), y = gridLines(1);
    ASSERT_EQ(int(x.size()), n + 1);
    ASSERT_EQ(int(y.size()), n + 1);
    EXPECT_NEAR((x[n] - x[n - 1])/(x[1] - x[0]), 4.0, 1e-9);
    EXPECT_NEAR((y[n] - y[n - 1])/(y[1] - y[0]), 0.25, 1e-9);
}


// * * * * * * * * * * * * * * * Invalid input * * * * * * * * * * * * * * * //

TEST_F(MeshConvert, threeDimensionalMeshIsRejected)
{
    copyCase("threeD");
    if (HasFatalFailure()) return;
    const std::string text = convertExpectingFailure();
    EXPECT_NE(text.find("not 2D"), std::string::npos) << text;
    EXPECT_NE(text.find("empty"), std::string::npos) << text;
}


TEST_F(MeshConvert, cellWithoutZoneIsRejected)
{
    copyCase("cellWithoutZone");
    if (HasFatalFailure()) return;
    const std::string text = convertExpectingFailure();
    EXPECT_NE(text.find("4 of 8 cells are in no cellZone"), std::string::npos)
        << text;
    // The example cell is one of the unzoned block (x > 1)
    EXPECT_NE(text.find("(1.25 0.25 0.05)"), std::string::npos) << text;
}


TEST_F(MeshConvert, meshWithoutCellZonesIsRejected)
{
    copyCase("noZones");
    if (HasFatalFailure()) return;
    const std::string text = convertExpectingFailure();
    EXPECT_NE(text.find("no cellZones"), std::string::npos) << text;
    EXPECT_NE(text.find("blockMeshDict"), std::string::npos) << text;
}


TEST_F(MeshConvert, zoneWithoutMaterialIsRejected)
{
    copyCase("twoZone");
    if (HasFatalFailure()) return;
    writeDictionary
    (
        caseDir_/"constant"/"spemProperties",
        "constant",
        "regions\n{\n    water { model weaklyCompressibleNewtonian; rho 1000;"
        " c 100; mu 1e-3; }\n}\n"
    );
    const std::string text = convertExpectingFailure();
    EXPECT_NE(text.find("FATAL IO ERROR"), std::string::npos) << text;
    EXPECT_NE(text.find("regions/plate"), std::string::npos) << text;
    EXPECT_NE(text.find("constant/spemProperties"), std::string::npos)
        << text;
}


TEST_F(MeshConvert, badSplitValueIsRejectedNamingKeywordAndFile)
{
    copyCase("twoZone");
    if (HasFatalFailure()) return;
    writeDictionary
    (
        caseDir_/"system"/"spemMeshConvertDict",
        "system",
        "split   diagonal;"
    );
    const std::string text = convertExpectingFailure();
    EXPECT_NE(text.find("FATAL IO ERROR"), std::string::npos) << text;
    EXPECT_NE(text.find("'split'"), std::string::npos) << text;
    EXPECT_NE(text.find("diagonal"), std::string::npos) << text;
    EXPECT_NE(text.find("system/spemMeshConvertDict"), std::string::npos)
        << text;
}


// ************************************************************************* //
